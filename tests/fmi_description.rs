//! What the two generated model descriptions declare beyond their schema (issue 8, items 3 and 6):
//! - dependencies: after initialization no output depends on an input (an input set at a
//!   communication point acts from that point on; the outputs there were computed before it), so
//!   a master that sorts by dependencies sees no algebraic loop in a feedback coupling; in
//!   Initialization Mode the outputs depend on the inputs (the initial static deflection is under
//!   the tip forces) and the calculated parameters do not;
//! - units through `<TypeDefinitions>` and `declaredType` only: rust-fmi's reader refuses any
//!   attribute its schema does not list on a variable (`unit` on `Float64` among them);
//! - `min` / `max` of every parameter: exactly the range `Scenario::validate` accepts, checked at
//!   each bound and one representable step beyond it;
//! - a `generationDateAndTime` from the source, not the clock.
//!
//! The checks read the generated XML with a small scanner: the generator escapes `"`, `<` and `>`
//! in attribute values, so an element is `<Tag` up to the next `>`.

use beam_impact::fmi::description::{self, GENERATION_DATE_AND_TIME};
use beam_impact::fmi::variables::{table, Causality, Source, Type, Variable};
use beam_impact::model::parameters::{self, Parameter};
use beam_impact::{Error, Scenario};

/// The attributes of every `<tag ...>` element in `xml`, in order.
fn elements<'a>(xml: &'a str, tag: &str) -> Vec<Vec<(&'a str, &'a str)>> {
    let open = format!("<{tag} ");
    let mut found = Vec::new();
    let mut rest = xml;
    while let Some(at) = rest.find(&open) {
        let body = &rest[at + open.len()..];
        let end = body.find('>').expect("element ends");
        found.push(attributes(body[..end].trim_end_matches('/')));
        rest = &body[end..];
    }
    found
}

fn attributes(mut text: &str) -> Vec<(&str, &str)> {
    let mut list = Vec::new();
    loop {
        text = text.trim_start();
        let Some(eq) = text.find("=\"") else { break };
        let name = &text[..eq];
        let value_start = eq + 2;
        let len = text[value_start..].find('"').expect("attribute value ends");
        list.push((name, &text[value_start..value_start + len]));
        text = &text[value_start + len + 1..];
    }
    list
}

fn get<'a>(attrs: &[(&str, &'a str)], name: &str) -> Option<&'a str> {
    attrs.iter().find(|(n, _)| *n == name).map(|(_, v)| *v)
}

fn numbers(list: &str) -> Vec<u32> {
    list.split_whitespace().map(|x| x.parse().unwrap()).collect()
}

fn by_vr(vr: u32) -> Variable {
    table().into_iter().nth(vr as usize).unwrap()
}

/// Value references of the inputs.
fn inputs() -> Vec<u32> {
    table().iter().filter(|v| v.causality == Causality::Input).map(|v| v.vr).collect()
}

#[test]
fn no_output_depends_on_an_input_after_initialization_fmi2() {
    let xml = description::fmi2();
    let outputs = xml.split("<Outputs>").nth(1).unwrap().split("</Outputs>").next().unwrap();
    let initial = xml.split("<InitialUnknowns>").nth(1).unwrap().split("</InitialUnknowns>").next().unwrap();
    let unknowns = elements(outputs, "Unknown");
    assert_eq!(unknowns.len(), table().iter().filter(|v| v.causality == Causality::Output).count());
    for u in &unknowns {
        assert_eq!(get(u, "dependencies"), Some(""), "output {u:?}: an absent attribute means every input");
    }
    let input_indices: Vec<u32> = inputs().iter().map(|vr| vr + 1).collect();
    for u in elements(initial, "Unknown") {
        let v = by_vr(get(&u, "index").unwrap().parse::<u32>().unwrap() - 1);
        let deps = numbers(get(&u, "dependencies").expect("initial unknowns list their dependencies"));
        let on_inputs = input_indices.iter().all(|i| deps.contains(i));
        let on_no_input = input_indices.iter().all(|i| !deps.contains(i));
        match v.causality {
            Causality::Output => assert!(on_inputs, "{}: {deps:?}", v.name),
            _ => assert!(on_no_input, "{}: {deps:?}", v.name),
        }
        for d in deps {
            let k = by_vr(d - 1);
            let allowed = matches!(k.source, Source::Parameter(_) | Source::Input(_) | Source::Motion(_));
            assert!(allowed, "{} depends on {}", v.name, k.name);
        }
    }
}

#[test]
fn no_output_depends_on_an_input_after_initialization_fmi3() {
    let xml = description::fmi3();
    let outputs = elements(&xml, "Output");
    assert_eq!(outputs.len(), table().iter().filter(|v| v.causality == Causality::Output).count());
    for o in &outputs {
        assert_eq!(get(o, "dependencies"), Some(""), "output {o:?}: an absent attribute means every input");
    }
    let inputs = inputs();
    let initial = elements(&xml, "InitialUnknown");
    assert!(!initial.is_empty());
    for u in initial {
        let v = by_vr(get(&u, "valueReference").unwrap().parse().unwrap());
        let deps = numbers(get(&u, "dependencies").expect("initial unknowns list their dependencies"));
        match v.causality {
            Causality::Output => assert!(inputs.iter().all(|i| deps.contains(i)), "{}: {deps:?}", v.name),
            _ => assert!(inputs.iter().all(|i| !deps.contains(i)), "{}: {deps:?}", v.name),
        }
        // Every parameter the values depend on is listed (energy_tolerance only judges the run).
        for k in table() {
            if let Source::Parameter(p) = k.source {
                assert_eq!(deps.contains(&k.vr), p.name != "energy_tolerance", "{} on {}", v.name, k.name);
            }
        }
    }
}

/// The attributes rust-fmi (fmi-schema, FMI 3) reads on a variable element; it refuses any other.
const STRICT_FLOAT: &[&str] = &[
    "name",
    "valueReference",
    "description",
    "causality",
    "variability",
    "canHandleMultipleSetPerTimeInstant",
    "clocks",
    "declaredType",
    "intermediateUpdate",
    "previous",
    "start",
    "initial",
    "min",
    "max",
    "derivative",
    "reinit",
];

#[test]
fn fmi3_variables_carry_only_attributes_a_strict_reader_knows() {
    let xml = description::fmi3();
    let strict_int: Vec<&str> =
        STRICT_FLOAT.iter().copied().filter(|a| !["derivative", "reinit"].contains(a)).collect();
    for (tag, allowed) in
        [("Float64", STRICT_FLOAT.to_vec()), ("Int32", [strict_int.clone(), vec!["quantity"]].concat())]
    {
        for e in elements(&xml, tag) {
            for (name, _) in &e {
                assert!(allowed.contains(name), "{tag} {:?} has attribute {name}", get(&e, "name"));
            }
        }
    }
    for tag in ["Boolean", "String"] {
        for e in elements(&xml, tag) {
            for (name, _) in &e {
                assert!(strict_int.contains(name) && *name != "min" && *name != "max", "{tag} has {name}");
            }
        }
    }
}

#[test]
fn units_are_declared_through_type_definitions() {
    let fmi3 = description::fmi3();
    let fmi2 = description::fmi2();
    let types3 = elements(&fmi3, "Float64Type");
    let types2: Vec<_> = fmi2
        .split("<SimpleType ")
        .skip(1)
        .map(|s| {
            let name = attributes(&s[..s.find('>').unwrap()]);
            let real = elements(s.split("</SimpleType>").next().unwrap(), "Real");
            (get(&name, "name").unwrap().to_string(), real[0].clone())
        })
        .collect();
    assert_eq!(types3.len(), types2.len());
    let unit_of = |declared: &str| {
        let t3 = types3.iter().find(|t| get(t, "name") == Some(declared)).expect("FMI 3 type defined");
        let (_, t2) = types2.iter().find(|(n, _)| n == declared).expect("FMI 2 type defined");
        assert_eq!(get(t3, "unit"), get(t2, "unit"));
        assert_eq!(get(t3, "displayUnit"), get(t2, "displayUnit"));
        get(t3, "unit").unwrap().to_string()
    };
    let v3: Vec<_> = elements(&fmi3, "Float64");
    let v2: Vec<_> = elements(fmi2.split("<ModelVariables>").nth(1).unwrap(), "Real");
    assert_eq!(v3.len(), v2.len());
    let reals: Vec<Variable> = table().into_iter().filter(|v| v.ty == Type::Real).collect();
    assert_eq!(reals.len(), v3.len());
    for ((v, e3), e2) in reals.iter().zip(&v3).zip(&v2) {
        assert!(get(e2, "unit").is_none() && get(e2, "displayUnit").is_none(), "{}: {e2:?}", v.name);
        assert_eq!(get(e3, "declaredType"), get(e2, "declaredType"), "{}", v.name);
        match v.unit {
            Some(unit) => assert_eq!(unit_of(get(e3, "declaredType").unwrap()), unit, "{}", v.name),
            None => assert!(get(e3, "declaredType").is_none(), "{}", v.name),
        }
    }
    // Stresses and moduli display in MPa through their type.
    assert!(types3.iter().any(|t| get(t, "unit") == Some("Pa") && get(t, "displayUnit") == Some("MPa")));
}

#[test]
fn generation_date_and_time_comes_from_the_source() {
    let shape = GENERATION_DATE_AND_TIME.as_bytes();
    assert_eq!(shape.len(), 20, "{GENERATION_DATE_AND_TIME}");
    for (i, c) in shape.iter().enumerate() {
        let expected_separator = match i {
            4 | 7 => Some(b'-'),
            10 => Some(b'T'),
            13 | 16 => Some(b':'),
            19 => Some(b'Z'),
            _ => None,
        };
        match expected_separator {
            Some(s) => assert_eq!(*c, s, "{GENERATION_DATE_AND_TIME}"),
            None => assert!(c.is_ascii_digit(), "{GENERATION_DATE_AND_TIME}"),
        }
    }
    for xml in [description::fmi2(), description::fmi3()] {
        let root = &elements(&xml, "fmiModelDescription")[0];
        assert_eq!(get(root, "generationDateAndTime"), Some(GENERATION_DATE_AND_TIME));
    }
    assert_eq!(description::fmi2(), description::fmi2());
}

/// Whether the FMU accepts `value` for `p`: `parameters::set` (what the setters call) and then
/// `Scenario::validate` (what initialization calls) on a scenario where the rules that tie two
/// parameters together are at their widest: `upper.length` at its largest, 1 km (`drop_height` up
/// to half of it, `contact_position` up to it), and `drop_height` and `contact_position` small
/// enough for the shortest bridge, 1 cm; for `gravity`, a stated impact speed (issue 28: gravity 0
/// needs one).
fn accepted(p: &Parameter, value: f64) -> std::result::Result<(), String> {
    let mut s = Scenario::default();
    s.upper.length = 1e3;
    s.drop_height = 0.0;
    s.contact_position = 0.005;
    if p.name == "gravity" {
        s.impact_angular_velocity = Some(1.0);
    }
    // Issue 45: the struck beam's contact reaches its longest beam's end (lower.length's max).
    if p.name == "lower.contact_position" {
        s.lower.length = 1e3;
    }
    // A power law needs its rate in N/m^n; the exponent is the power law's (issue 40: given with
    // the linear law it is refused).
    if p.name == "contact.law" {
        s.contact.given_stiffness = Some(1e9);
    }
    // Hertz's law takes its constant from a radius and both moduli, not a stiffness (issue 45).
    if p.name == "contact.law" && value == 2.0 {
        s.contact.given_stiffness = None;
        // A 1 cm sphere: at 3.5 cm the 1 km bridge's weight makes Hertz's rate 4.5e10 N/m,
        // above every law's 4e10 (issue 40 item 3).
        s.upper.radius = 0.01;
    }
    // A speed is a rigid impactor's (issue 45).
    if p.name == "impact_speed" {
        s.upper.kind = beam_impact::model::scenario::ImpactorKind::Mass;
    }
    // The declared range of contact.stiffness is the power law's (N/m^n); the linear law's stops
    // at 4e10 N/m, and any law's rate at 4e10 N/m (issue 40): the top of the declared range as a
    // power law of exponent 3 whose tangent at twice the static compression under the bridge's
    // weight (the contact at its free end, no drop) is 3.9e8 N/m.
    if p.name == "contact.stiffness" && value > beam_impact::model::scenario::MAX_CONTACT_STIFFNESS {
        s.contact.law = beam_impact::model::contact_law::LawKind::Power;
        s.contact.exponent = 3.0;
        s.contact.given_stiffness = Some(1e9);
        s.contact_position = s.upper.length;
    }
    // The bar's E A / l is held to 4e10 N/m as a whole: each of its fields at its declared end
    // with the others' at a bar that stays within it.
    if ["contact.area", "contact.elastic_modulus", "contact.length"].contains(&p.name) {
        s.contact.length = 1e3;
        s.contact.area = 1e-3;
        s.contact.elastic_modulus = 1e6;
    }
    if p.name == "contact.exponent" {
        s.contact.law = beam_impact::model::contact_law::LawKind::Power;
        // 1e6 N/m^n: at the exponent's top (3) the 1 km bridge's weight on 1e9 N/m^3 makes a rate
        // of 6.2e10 N/m, above every law's 4e10 (issue 40 item 3); 1e6 gives 6.2e9.
        s.contact.given_stiffness = Some(1e6);
    }
    s.validate().expect("the base scenario is valid");
    let outcome = parameters::set(&mut s, p, value).and_then(|()| s.validate());
    match outcome {
        Ok(()) => Ok(()),
        Err(Error::InvalidParameter { name, .. }) if name == p.name => Err(format!("{name} refused")),
        Err(e) => panic!("{} = {value}: an error about another field: {e}", p.name),
    }
}

#[test]
fn declared_parameter_ranges_are_what_validation_accepts() {
    let fmi2 = description::fmi2();
    let fmi3 = description::fmi3();
    let mut checked = 0;
    for v in table() {
        let Source::Parameter(p) = v.source else { continue };
        // The declared bounds are the ones written in both descriptions.
        let e3 = elements(&fmi3, if v.ty == Type::Integer { "Int32" } else { "Float64" })
            .into_iter()
            .find(|e| get(e, "name") == Some(v.name.as_str()))
            .unwrap();
        let parse = |x: Option<&str>| x.map(|x| x.parse::<f64>().unwrap());
        assert_eq!((parse(get(&e3, "min")), parse(get(&e3, "max"))), (v.min, v.max), "{}", v.name);
        let index = format!("<!-- index {} -->", v.vr + 1);
        let e2 = &elements(fmi2.split(&index).nth(1).unwrap(), v.ty.fmi2_name())[0];
        assert_eq!((parse(get(e2, "min")), parse(get(e2, "max"))), (v.min, v.max), "{}", v.name);

        let integer = v.ty == Type::Integer;
        let below = |x: f64| if integer { x - 1.0 } else { x.next_down() };
        let above = |x: f64| if integer { x + 1.0 } else { x.next_up() };
        let min = v.min.unwrap_or_else(|| panic!("{}: no min declared", v.name));
        assert_eq!(accepted(p, min), Ok(()), "{} at its min {min:e}", v.name);
        assert!(accepted(p, below(min)).is_err(), "{} below its min {min:e}: {:e} accepted", v.name, below(min));
        match v.max {
            Some(max) => {
                assert_eq!(accepted(p, max), Ok(()), "{} at its max {max:e}", v.name);
                assert!(accepted(p, above(max)).is_err(), "{} above its max {max:e}: accepted", v.name);
            }
            // Up to upper.length (its free end, issue 28), a bound that depends on another
            // parameter: no max.
            None => {
                assert_eq!(v.name, "contact_position", "{}: no max declared", v.name);
                assert!(accepted(p, 1e3).is_ok() && accepted(p, 1e3f64.next_up()).is_err());
            }
        }
        checked += 1;
    }
    assert_eq!(checked, table().iter().filter(|v| matches!(v.source, Source::Parameter(_))).count());
    assert!(checked >= 27, "{checked}");
}

/// Issue 40: every range a user reads (the `scenario` listing, and each FMU parameter's
/// description where `min` / `max` cannot say it all) comes from the table validation takes its
/// numbers from, and holds: a gap's smallest nonzero value (a yield stress from 1 kPa, a step
/// from 1 ns, ...) is accepted and the next value below it refused; the linear law's contact
/// stiffness stops at 4e10 N/m as its rule says, the power law's at the declared 1e13 N/m^n.
#[test]
fn every_documented_range_and_gap_is_what_validation_accepts() {
    let listing = parameters::annotate_toml(&Scenario::default().to_toml());
    let table = table();
    let mut gaps = 0;
    for p in parameters::PARAMETERS {
        let Some(text) = parameters::range_text(p.name) else { continue };
        let key = p.name.rsplit('.').next().unwrap();
        let listed = listing.lines().any(|l| {
            (l.starts_with(&format!("{key} = ")) || l.starts_with(&format!("# {key} = ")))
                && l.ends_with(&format!("; range {text}"))
        });
        assert!(listed || p.name == "duration", "{}: the listing does not say 'range {text}'", p.name);
        if let Some(note) = parameters::range_note(p.name) {
            let v = table.iter().find(|v| v.name == p.name).unwrap();
            assert!(v.description.ends_with(&note), "{}: {}", p.name, v.description);
        }
        if let (Some(gap), parameters::Kind::Real) = (parameters::nonzero_minimum(p.name), p.kind) {
            assert!(text.contains(", or "), "{}: {text}", p.name);
            assert_eq!(accepted(p, gap), Ok(()), "{} at its smallest nonzero value {gap:e}", p.name);
            assert!(accepted(p, gap.next_down()).is_err(), "{} just below {gap:e}: accepted", p.name);
            assert_eq!(accepted(p, 0.0), Ok(()), "{} at 0", p.name);
            gaps += 1;
        }
    }
    assert!(gaps >= 7, "{gaps}");
    // contact.stiffness: the linear law's rule, as its range states it.
    let mut s = Scenario::default();
    let stiffness = parameters::find("contact.stiffness").unwrap();
    parameters::set(&mut s, stiffness, 4e10).unwrap();
    assert!(s.validate().is_ok());
    parameters::set(&mut s, stiffness, 4e10f64.next_up()).unwrap();
    let e = s.validate().unwrap_err().to_string();
    assert!(e.contains("contact.stiffness") && e.contains("4e10"), "{e}");
    assert!(parameters::range_text("contact.stiffness").unwrap().contains("at most 4e10 N/m with contact.law"));
}

/// Issue 27: each support-motion input declares `min` / `max` in both descriptions, its range
/// (`MOTION_LIMITS`, stated in its description too), and those are exactly what the FMU's setter
/// accepts: the bounds are, one representable step beyond them is refused with an error.
#[test]
fn declared_motion_input_ranges_are_what_the_setters_accept() {
    use crate::fmi_common::importer::{load, Fmu2, ERROR, OK};
    use beam_impact::model::support_motion::{MOTION_LIMITS, MOTION_UNITS};
    let (fmi2, fmi3) = (description::fmi2(), description::fmi3());
    let fmu = Fmu2::new(&load());
    let mut checked = 0;
    for v in table() {
        let Source::Motion(k) = v.source else { continue };
        let limit = MOTION_LIMITS[k];
        assert_eq!((v.min, v.max), (Some(-limit), Some(limit)), "{}", v.name);
        let e3 = elements(&fmi3, "Float64").into_iter().find(|e| get(e, "name") == Some(v.name.as_str())).unwrap();
        let index = format!("<!-- index {} -->", v.vr + 1);
        let e2 = elements(fmi2.split(&index).nth(1).unwrap(), "Real").remove(0);
        for e in [&e3, &e2] {
            let parse = |name: &str| get(e, name).map(|x| x.parse::<f64>().unwrap());
            assert_eq!((parse("min"), parse("max")), (Some(-limit), Some(limit)), "{}", v.name);
        }
        assert!(v.description.contains(&format!("|value| <= {limit} {}", MOTION_UNITS[k])), "{}", v.description);
        for bound in [-limit, limit] {
            assert_eq!(fmu.set(&v.name, bound), OK, "{} at {bound}: {}", v.name, fmu.log.text());
        }
        for beyond in [(-limit).next_down(), limit.next_up()] {
            assert_eq!(fmu.set(&v.name, beyond), ERROR, "{} at {beyond:e} accepted", v.name);
        }
        assert_eq!(fmu.set(&v.name, 0.0), OK);
        checked += 1;
    }
    assert_eq!(checked, MOTION_LIMITS.len());
}
