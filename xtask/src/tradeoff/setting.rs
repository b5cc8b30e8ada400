//! One point in the space of the knobs that trade speed for accuracy on the
//! Brazilian disc, and the plans of runs (one knob at a time from a
//! reference, a few combinations, and the anchor every error is measured
//! against).

use anyhow::Result;
use toml::{Table, Value};

use crate::validate::brazilian::case::{Base, Mesh, set_contact, set_material};

/// The knobs of one run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Setting {
    /// Target in-plane triangle edge of the disc, m; the layers through the
    /// thickness are `round(t / h)` and the platens are meshed at `h`.
    pub h: f64,
    /// Platen speed V_y, m/s (each platen; Eq. 22's strain rate is 2V/d).
    pub velocity: f64,
    /// Joint penalty as a multiple of Young's modulus, p0 / E (Eq. 9).
    pub penalty: f64,
    /// `[solver] safety`: the fraction of the critical step.
    pub safety: f64,
    /// `[solver] mass_scaling`.
    pub mass_scaling: f64,
    /// `[contact] buffer`, m.
    pub buffer: f64,
    /// `[contact] model = "gradient"` (the energy-conserving contact)
    /// instead of Eq. 17's `"potential"`.
    pub gradient: bool,
}

/// What a run varies, for the report's grouping.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum Knob {
    /// The reference setting every one-at-a-time change starts from.
    Reference,
    /// Element size.
    Mesh,
    /// Loading rate.
    Rate,
    /// Joint penalty p0 / E.
    Penalty,
    /// Time-step safety factor.
    Safety,
    /// Mass scaling.
    MassScaling,
    /// Contact buffer.
    Buffer,
    /// The normal contact force (`[contact] model`).
    ContactModel,
    /// Several knobs at once.
    Combination,
}

impl Knob {
    /// Its name in the report.
    pub fn name(self) -> &'static str {
        match self {
            Knob::Reference => "reference",
            Knob::Mesh => "element size",
            Knob::Rate => "loading rate",
            Knob::Penalty => "penalty p0/E",
            Knob::Safety => "time-step safety",
            Knob::MassScaling => "mass scaling",
            Knob::Buffer => "contact buffer",
            Knob::ContactModel => "contact model",
            Knob::Combination => "combination",
        }
    }
}

impl Setting {
    /// The reference setting at element size `h`: the paper's fastest rate
    /// (0.1 m/s), p0 = 10 E, safety 0.9, no mass scaling, a 0.2 mm buffer,
    /// Eq. 17's contact.
    pub fn reference(h: f64) -> Setting {
        Setting { h, velocity: 0.1, penalty: 10.0, safety: 0.9, mass_scaling: 1.0, buffer: 2.0e-4, gradient: false }
    }

    /// A short label of the setting, e.g. `h4 V0.1 p10 s0.9 m1 b0.2`
    /// (h and b in mm; ` gradient` appended for the energy-conserving
    /// contact), also the name of its run directory.
    pub fn key(&self) -> String {
        format!(
            "h{} V{} p{} s{} m{} b{}{}",
            1e3 * self.h,
            self.velocity,
            self.penalty,
            self.safety,
            self.mass_scaling,
            1e3 * self.buffer,
            if self.gradient { " gradient" } else { "" }
        )
    }

    /// Layers of prisms through a disc of thickness `t`.
    pub fn layers(&self, t: f64) -> i64 {
        ((t / self.h).round() as i64).max(2)
    }

    /// The case of this setting, as TOML text.
    pub fn case(&self, base: &Base) -> Result<String> {
        let mesh =
            Mesh { element_size: self.h, layers: self.layers(base.disc.thickness), platen_size: self.h, gmsh: None };
        let young = base.disc.young;
        let s = *self;
        let title = format!("Brazilian disc, {} (cargo xtask tradeoff)", self.key());
        base.case(&title, mesh, self.velocity, &|t: &mut Table| {
            set_material(t, "penalty", Value::Float(s.penalty * young));
            set_contact(t, "buffer", Value::Float(s.buffer));
            if s.gradient {
                set_contact(t, "model", Value::String("gradient".into()));
            }
            if let Some(solver) = t.get_mut("solver").and_then(Value::as_table_mut) {
                solver.insert("safety".into(), s.safety.into());
                solver.insert("mass_scaling".into(), s.mass_scaling.into());
            }
        })
    }
}

/// A profile's runs: each setting with the knob it varies; the anchor is
/// the most accurate setting of the profile (the slowest rate on the
/// finest mesh it runs at that rate).
#[derive(Debug, Clone)]
pub struct Plan {
    /// The reference setting.
    pub reference: Setting,
    /// The anchor: errors are relative to its peak load.
    pub anchor: Setting,
    /// Every run, in the order they are made.
    pub runs: Vec<(Knob, Setting)>,
}

impl Plan {
    /// The plan of the quick (`--quick`) or the full profile.
    pub fn new(quick: bool) -> Plan {
        // The reference is the fastest of the paper's rates on the
        // validation's quick mesh (4 mm) or on a 3 mm mesh. The anchor is
        // the slowest rate (0.01 m/s, quasi-static in Fig. 6) on the
        // finest mesh of the full profile, and on the reference's 4 mm in
        // the quick one: 3 mm at 0.01 m/s alone would take most of the
        // quick profile's half hour, so the quick profile measures the
        // 3 mm mesh at the reference's rate only.
        let (sizes, h_ref, h_fine): (&[f64], f64, f64) =
            if quick { (&[6.0e-3, 5.0e-3, 3.0e-3], 4.0e-3, 4.0e-3) } else { (&[4.0e-3, 2.0e-3], 3.0e-3, 2.0e-3) };
        let r = Setting::reference(h_ref);
        let anchor = Setting { h: h_fine, velocity: 0.01, ..r };
        let mut runs = vec![(Knob::Reference, r)];
        let mut add = |knob: Knob, s: Setting| {
            if !runs.iter().any(|(_, t)| *t == s) {
                runs.push((knob, s));
            }
        };
        for &h in sizes {
            add(Knob::Mesh, Setting { h, ..r });
        }
        for velocity in [0.05, 0.02, 0.01] {
            add(Knob::Rate, Setting { velocity, ..r });
        }
        for penalty in [1.0, 3.0] {
            add(Knob::Penalty, Setting { penalty, ..r });
        }
        for safety in [0.3, 0.6] {
            add(Knob::Safety, Setting { safety, ..r });
        }
        for mass_scaling in [10.0, 100.0] {
            add(Knob::MassScaling, Setting { mass_scaling, ..r });
        }
        for buffer in [0.0, 8.0e-4] {
            add(Knob::Buffer, Setting { buffer, ..r });
        }
        add(Knob::ContactModel, Setting { gradient: true, ..r });
        let coarse = sizes[0];
        // The cheapest corner; a slow rate bought back with mass scaling
        // (V/10 with 100× the mass takes the reference's step count); a
        // soft penalty with mass scaling.
        add(Knob::Combination, Setting { h: coarse, mass_scaling: 10.0, penalty: 3.0, ..r });
        add(Knob::Combination, Setting { velocity: 0.01, mass_scaling: 100.0, ..r });
        add(Knob::Combination, Setting { velocity: 0.02, mass_scaling: 10.0, ..r });
        add(Knob::Combination, Setting { penalty: 3.0, mass_scaling: 10.0, ..r });
        add(Knob::Rate, anchor);
        Plan { reference: r, anchor, runs }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn plans_vary_one_knob_at_a_time_and_hold_the_anchor_once() {
        for quick in [true, false] {
            let plan = Plan::new(quick);
            let r = plan.reference;
            assert_eq!(plan.runs.iter().filter(|(_, s)| *s == plan.anchor).count(), 1);
            for (knob, s) in &plan.runs {
                let changed = [
                    s.h != r.h,
                    s.velocity != r.velocity,
                    s.penalty != r.penalty,
                    s.safety != r.safety,
                    s.mass_scaling != r.mass_scaling,
                    s.buffer != r.buffer,
                    s.gradient != r.gradient,
                ]
                .iter()
                .filter(|c| **c)
                .count();
                match knob {
                    Knob::Reference => assert_eq!(changed, 0),
                    Knob::Combination => assert!(changed >= 2, "{}", s.key()),
                    // The anchor of the full profile changes mesh and rate.
                    _ if *s == plan.anchor => assert!(changed >= 1),
                    _ => assert_eq!(changed, 1, "{}", s.key()),
                }
            }
            let keys: Vec<String> = plan.runs.iter().map(|(_, s)| s.key()).collect();
            let mut unique = keys.clone();
            unique.sort();
            unique.dedup();
            assert_eq!(unique.len(), keys.len(), "run directories are unique");
        }
    }

    #[test]
    fn layers_follow_the_element_size() {
        let s = Setting::reference;
        assert_eq!(s(4.0e-3).layers(0.015), 4);
        assert_eq!(s(2.0e-3).layers(0.015), 8);
        assert_eq!(s(6.0e-3).layers(0.015), 3);
        assert_eq!(s(1.0e-1).layers(0.015), 2);
    }
}
