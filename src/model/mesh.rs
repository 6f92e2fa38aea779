//! Node positions and DOF numbering of one beam (paper Fig. 5).

/// One node: its position and the indices of its free DOFs (None = constrained).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Node {
    /// Distance from the beam's first node (the clamp or the hinge), m.
    pub x: f64,
    /// Index of the deflection DOF w (up positive), if free.
    pub w: Option<usize>,
    /// Index of the rotation DOF theta = dw/dx, if free.
    pub theta: Option<usize>,
}

/// The nodes of a beam and its number of free DOFs. Element e joins nodes e and e + 1.
#[derive(Clone, Debug, PartialEq)]
pub struct Mesh {
    /// Nodes from the first (supported) end to the free end.
    pub nodes: Vec<Node>,
    /// Number of free DOFs.
    pub dofs: usize,
    /// How the first node is supported.
    pub support: Support,
    /// How the last node is held (issue 45: free for the paper's beams, else a second support).
    pub far: FarEnd,
    /// The node carrying a beam's lumped mass (`lower.tip_mass`): the free end, or on a beam
    /// with two supports its contact node.
    pub lumped: usize,
}

/// How the last node of a beam is held (issue 45: the struck beam on two supports).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum FarEnd {
    /// Free (the paper's cantilever and bridge).
    #[default]
    Free,
    /// Deflection fixed, rotation free (simply supported).
    Pinned,
    /// Deflection and rotation fixed.
    Clamped,
}

/// How the first node is supported.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Support {
    /// Deflection and rotation fixed (the arrestor's clamp).
    Clamped,
    /// Deflection fixed, rotation free (the bridge's hinge).
    Hinged,
    /// Every node fixed: a rigid support (issue 28), a beam without free DOFs.
    Rigid,
    /// A rigid impactor (issue 45): the first node fixed, the last node's deflection free and
    /// its rotation held, so that the one DOF is the body's vertical translation.
    Mass,
}

impl Support {
    /// Rigid-body modes of a beam with this support at one end and the other end free: a clamp
    /// leaves none, a hinge one (the rotation about it). The eigen solvers take this count from
    /// the model rather than guessing it from the size of an eigenvalue, which round-off makes
    /// unreliable on fine meshes (the absolute error grows like omega_max^2 ~ N^4).
    pub fn rigid_modes(self) -> usize {
        match self {
            Support::Clamped | Support::Rigid => 0,
            Support::Hinged | Support::Mass => 1,
        }
    }
}

/// Node positions from `start` to `end` with about `elements` elements and a node at each of
/// `breaks` (strictly inside): each interval between breaks takes its share of the elements by
/// length, at least one, equally spaced within it.
fn spread(start: f64, end: f64, elements: usize, breaks: &[f64]) -> Vec<f64> {
    let mut points = vec![start];
    points.extend(breaks.iter().copied().filter(|&b| b > start && b < end));
    points.push(end);
    let total = end - start;
    let mut x = vec![start];
    for pair in points.windows(2) {
        let (a, b) = (pair[0], pair[1]);
        let n = ((elements as f64 * (b - a) / total).round() as usize).max(1);
        x.extend((1..=n).map(|i| if i == n { b } else { a + (b - a) * i as f64 / n as f64 }));
    }
    x
}

impl Mesh {
    /// A beam from node positions `x` (ascending, first = support), numbering free DOFs node by node.
    pub fn new(x: &[f64], support: Support) -> Mesh {
        Mesh::with_far_end(x, support, FarEnd::Free)
    }

    /// [`Self::new`] with the last node held by `far` too (issue 45): its deflection (pinned)
    /// or deflection and rotation (clamped) constrained.
    pub fn with_far_end(x: &[f64], support: Support, far: FarEnd) -> Mesh {
        let last = x.len().saturating_sub(1);
        let mut dofs = 0;
        let mut next = || {
            dofs += 1;
            Some(dofs - 1)
        };
        let nodes = x
            .iter()
            .enumerate()
            .map(|(i, &x)| {
                let (w, theta) = match (i, support) {
                    (_, Support::Rigid) | (0, Support::Clamped) => (None, None),
                    (0, Support::Hinged) => (None, next()),
                    (0, Support::Mass) => (None, None),
                    (_, Support::Mass) => (next(), None),
                    _ if i == last && far == FarEnd::Clamped => (None, None),
                    _ if i == last && far == FarEnd::Pinned => (None, next()),
                    _ => (next(), next()),
                };
                Node { x, w, theta }
            })
            .collect();
        Mesh { nodes, dofs, support, far, lumped: last }
    }

    /// The struck beam (issue 45): `length` m held at x = 0 by `support` and at its far end by
    /// `far`, about `elements` elements with a node at every section change `breaks` and at
    /// `contact` (m from the first support; at the far end, the last node). Returns the mesh and
    /// the contact node. A clamped-free beam struck at its free end without section changes is
    /// [`Self::cantilever`] bit for bit. A lumped mass sits at the free end, or with a far
    /// support at the contact node.
    pub fn struck_beam(
        length: f64,
        elements: usize,
        breaks: &[f64],
        support: Support,
        far: FarEnd,
        contact: f64,
    ) -> (Mesh, usize) {
        let inside = contact > 0.0 && contact < length;
        let mut all: Vec<f64> = breaks.to_vec();
        if inside && !breaks.contains(&contact) {
            all.push(contact);
            all.sort_by(f64::total_cmp);
        }
        let x = if all.is_empty() {
            (0..=elements).map(|i| length * i as f64 / elements as f64).collect()
        } else {
            spread(0.0, length, elements, &all)
        };
        let node = if inside { x.iter().position(|&p| p == contact).unwrap_or(x.len() - 1) } else { x.len() - 1 };
        let mut mesh = Mesh::with_far_end(&x, support, far);
        if far != FarEnd::Free {
            mesh.lumped = node;
        }
        (mesh, node)
    }

    /// A clamped-free beam of `elements` equal elements.
    pub fn cantilever(length: f64, elements: usize) -> Mesh {
        let x: Vec<f64> = (0..=elements).map(|i| length * i as f64 / elements as f64).collect();
        Mesh::new(&x, Support::Clamped)
    }

    /// A clamped-free beam of about `elements` elements with a node at every section change
    /// `breaks` (ascending, inside the beam; none: [`Self::cantilever`], bit for bit).
    pub fn cantilever_sections(length: f64, elements: usize, breaks: &[f64]) -> Mesh {
        if breaks.is_empty() {
            return Mesh::cantilever(length, elements);
        }
        Mesh::new(&spread(0.0, length, elements, breaks), Support::Clamped)
    }

    /// A rigid support of `length` m: one element, no free DOF.
    pub fn rigid(length: f64) -> Mesh {
        Mesh::new(&[0.0, length], Support::Rigid)
    }

    /// A rigid impactor (issue 45): one element of `length` m whose far node's deflection is the
    /// body's one DOF (the element carries neither stiffness nor mass: see
    /// [`crate::model::Beam::assemble`] with both 0 and the body as the tip mass).
    pub fn mass(length: f64) -> Mesh {
        Mesh::new(&[0.0, length], Support::Mass)
    }

    /// A hinged-free beam with a node at `contact_position`: `inner` equal elements up to it and
    /// `outer` equal elements beyond it. The contact node is node `inner`.
    pub fn hinged_free(length: f64, contact_position: f64, inner: usize, outer: usize) -> Mesh {
        let mut x: Vec<f64> = (0..=inner).map(|i| contact_position * i as f64 / inner as f64).collect();
        x.extend((1..=outer).map(|i| contact_position + (length - contact_position) * i as f64 / outer as f64));
        Mesh::new(&x, Support::Hinged)
    }

    /// [`Self::hinged_free`] with a node at every section change `breaks` as well (ascending,
    /// inside the beam; none: [`Self::hinged_free`], bit for bit). The contact node is the node
    /// at `contact_position`.
    pub fn hinged_free_sections(
        length: f64,
        contact_position: f64,
        inner: usize,
        outer: usize,
        breaks: &[f64],
    ) -> (Mesh, usize) {
        if breaks.is_empty() {
            return (Mesh::hinged_free(length, contact_position, inner, outer), inner);
        }
        let before: Vec<f64> = breaks.iter().copied().filter(|&b| b < contact_position).collect();
        let after: Vec<f64> = breaks.iter().copied().filter(|&b| b > contact_position).collect();
        let mut x = spread(0.0, contact_position, inner, &before);
        let contact = x.len() - 1;
        if outer > 0 {
            x.extend(spread(contact_position, length, outer, &after).into_iter().skip(1));
        }
        (Mesh::new(&x, Support::Hinged), contact)
    }

    /// Number of elements.
    pub fn elements(&self) -> usize {
        self.nodes.len() - 1
    }

    /// Length of element `e`, m.
    pub fn element_length(&self, e: usize) -> f64 {
        self.nodes[e + 1].x - self.nodes[e].x
    }

    /// Global DOF indices of element `e` in the order (w1, theta1, w2, theta2).
    pub fn element_dofs(&self, e: usize) -> [Option<usize>; 4] {
        let (a, b) = (self.nodes[e], self.nodes[e + 1]);
        [a.w, a.theta, b.w, b.theta]
    }

    /// Rigid-body modes of the beam, from its support: see [`Support::rigid_modes`]; none with
    /// a second support at the far end (issue 45: every such beam is held against rigid motion).
    pub fn rigid_modes(&self) -> usize {
        if self.far == FarEnd::Free {
            self.support.rigid_modes()
        } else {
            0
        }
    }

    /// The node carrying the beam's lumped mass ([`Mesh::lumped`]).
    pub fn lumped_node(&self) -> &Node {
        &self.nodes[self.lumped]
    }

    /// The free end's node.
    pub fn tip(&self) -> &Node {
        &self.nodes[self.nodes.len() - 1]
    }
}
