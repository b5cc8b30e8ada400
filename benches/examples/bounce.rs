//! A closed contact cycle: an elastic cube (40 mm, granite of Table 1,
//! undamped, no joints) thrown flat at `V` m/s onto a rigid plate,
//! frictionless, until it has left the plate for good; prints the energy
//! it brought and took away, and what the contact term of the energy
//! account holds after the bounce (zero for a force field with a
//! potential; its share of the impact energy is the cycle's residual).
//!
//! ```text
//! target/release/examples/bounce [SAFETY [V [TILT]]]
//! ```
//!
//! `SAFETY` (default 0.3) is the fraction of the contact-aware critical
//! step, `TILT` (default 0) tilts the cube about `x` by that many degrees
//! so that it lands on an edge. Pairs are evaluated as the solver's
//! defaults say (`ContactSettings::new`).

use femdem_core::Vec3;
use femdem_material::{ElasticParams, Law};
use femdem_mesh::generate::{BoxSpec, generate_box};
use femdem_mesh::{Region, insert_joints};
use femdem_solver::select::{NodeSelection, select_nodes};
use femdem_solver::{
    ContactSettings, Loads, Model, Ramp, RegionBehaviour, Solver, StepParams, VelocityDrive, Want, held_nodes,
    stable_time_step,
};

fn main() {
    let mut args = std::env::args().skip(1).map(|a| a.parse::<f64>().expect("a number"));
    let safety = args.next().unwrap_or(0.3);
    let speed = args.next().unwrap_or(1.0);
    let tilt = args.next().unwrap_or(0.0).to_radians();
    let (h, size, penalty) = (0.01, 0.04, 26e9);
    let cube = |min: [f64; 3], max: [f64; 3], name: &str| {
        generate_box(&BoxSpec {
            min,
            max,
            element_size: h,
            jitter: 0.0,
            seed: 1,
            region: Region { name: name.into(), breakable: false },
        })
        .expect("a box")
    };
    let gap = 0.25 * h;
    let mut mesh = cube([0.0, 0.0, gap], [size, size, gap + size], "cube");
    mesh.append(&cube([-h, -h, -h], [size + h, size + h, 0.0], "plate"));
    // Tilt the cube about the x axis through its centre.
    let centre = Vec3::new(0.5 * size, 0.5 * size, gap + 0.5 * size * (tilt.cos().abs() + tilt.sin().abs()));
    for p in mesh.coords.iter_mut() {
        if p[2] > 0.0 {
            let r = Vec3::from(*p) - Vec3::new(0.5 * size, 0.5 * size, gap + 0.5 * size);
            let (c, s) = (tilt.cos(), tilt.sin());
            *p = (centre + Vec3::new(r.x, c * r.y - s * r.z, s * r.y + c * r.z)).into();
        }
    }
    let jointed = insert_joints(&mesh).expect("joints");
    let granite =
        ElasticParams { young: 26e9, poisson: 0.2, density: 2340.0, viscosity: 0.0 }.validate().expect("granite");
    let behaviour =
        [RegionBehaviour::Deformable { law: Law::NeoHookean, material: granite, joints: None }, RegionBehaviour::Rigid];
    let model = Model::new(&jointed, &behaviour, 1.0).expect("a model");
    let plate = select_nodes(&jointed, &NodeSelection { region: Some("plate".into()), ..Default::default() })
        .expect("plate nodes");
    let loads = Loads {
        drives: vec![VelocityDrive {
            name: "plate".into(),
            nodes: plate,
            velocity: Vec3::zeros(),
            components: [true; 3],
            ramp: Ramp::STEP,
            start_time: None,
        }],
        ..Loads::default()
    };
    let held = held_nodes(&model, &loads).expect("held nodes");
    let omega = stable_time_step(&model, &held, 300).omega_max;
    // The contact springs stiffen the top frequency: `contact_omega`.
    let omega_c = femdem_solver::contact_omega(&model, penalty);
    let dt = safety * 2.0 / (omega * omega + omega_c * omega_c).sqrt();
    let mut s = Solver::new(model, loads, StepParams::new(dt).expect("a step")).expect("a solver");
    s.enable_contact(ContactSettings::new(penalty), &[]);
    s.set_velocity(|x| if x.z > 0.0 { Vec3::new(0.0, 0.0, -speed) } else { Vec3::zeros() });
    let energy = |s: &mut Solver| {
        s.step(Want { energy: true, ..Want::default() });
        *s.energies()
    };
    let before = energy(&mut s);
    let (mut touched, mut apart, mut steps) = (false, 0, 0);
    while apart < 500 && steps < 2_000_000 {
        s.step(Want::default());
        steps += 1;
        let pairs = s.contact().map_or(0, |c| c.active_pairs);
        touched |= pairs > 0;
        apart = if touched && pairs == 0 { apart + 1 } else { 0 };
    }
    let after = energy(&mut s);
    let brought = before.kinetic + before.tet_elastic;
    let took = after.kinetic + after.tet_elastic;
    println!("dt               {dt:.4e} s ({safety} of the contact-aware critical step), {steps} steps");
    println!("brought          {brought:.6e} J");
    println!("took away        {took:.6e} J ({:+.4}%)", 100.0 * (took / brought - 1.0));
    println!(
        "contact term     {:.6e} J ({:+.4}% of the impact energy)",
        after.contact,
        100.0 * after.contact / brought
    );
    println!("balance drift    {:.3e} J", after.balance() - before.balance());
}
