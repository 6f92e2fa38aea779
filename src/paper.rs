//! The values the paper prints (Tables 1-3, Figure 6): the targets of the comparison.

/// Table 1, FEM column: w_din,a (m), sigma_din,a, tau_din,a, sigma_din,b (Pa).
pub const TABLE1_FEM: [f64; 4] = [0.691, 492e6, 59e6, 295e6];
/// Table 1, energy approach column (same order).
pub const TABLE1_ENERGY: [f64; 4] = [0.628, 412e6, 40e6, 219e6];
/// E_def,a = 149.2 kJ (Eq. 35).
pub const ARRESTOR_STRAIN_ENERGY: f64 = 149.2e3;
/// E_def,b = 4.4 kJ (Eq. 36): the bridge's strain energy of the energy approach, at the largest
/// arrestor deflection with the bridge taken as a rigid body stopped by F_din (docs/scenario.md).
pub const BRIDGE_STRAIN_ENERGY: f64 = 4.4e3;
/// E_def,b / E_def,a: "the bridge strain energy makes only 3,0 % of the arrestor strain energy".
pub const BRIDGE_STRAIN_RATIO: f64 = 0.030;
/// Table 2: arrestor, bridge, coupled natural frequencies, rad/s.
pub const TABLE2: [[f64; 5]; 3] =
    [[13.7, 92.9, 270.9, 546.1, 923.5], [0.0, 55.9, 181.1, 377.9, 646.5], [5.6, 45.8, 84.4, 181.1, 251.8]];
/// Table 3: the natural periods, s (the bridge's rigid mode has none: NaN).
pub const TABLE3: [[f64; 5]; 3] =
    [[0.458, 0.068, 0.023, 0.012, 0.007], [f64::NAN, 0.112, 0.035, 0.017, 0.010], [1.130, 0.137, 0.074, 0.035, 0.025]];
/// Figure 6: the long separation, s.
pub const SEPARATION: (f64, f64) = (0.77, 1.44);
/// Steps the paper reports for 3 s.
pub const STEPS: u64 = 90_000;
