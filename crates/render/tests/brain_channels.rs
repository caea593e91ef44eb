//! A brain's channels are recorded, drawn and replayed whatever the robot kind: a graph brain and
//! an attention brain on a pressure-based soft agent, whose agent code knows neither.

use vsrlab_render::replay::{Replay, ReplayOptions};
use vsrlab_render::{render_frame, RenderOptions};
use vsrlab_tasks::{channels, episode, PsaRobot, TaskSpec, Trace, TraceLevel};

fn trace(brain: &str) -> Trace {
    let robot = PsaRobot::from_short_forms("psa:small", brain).unwrap();
    let mut task = TaskSpec::parse("locomotion:flat").unwrap();
    if let TaskSpec::Locomotion(l) = &mut task {
        l.duration = 1.0;
    }
    episode::run(&robot, task.task(), 0, TraceLevel::Full)
        .unwrap()
        .trace
        .unwrap()
}

/// Whether drawing the brain's layer changes the last frame.
fn drawn(trace: &Trace) -> bool {
    let last = trace.len() - 1;
    let on = render_frame(trace, last, &RenderOptions::default());
    let off = RenderOptions {
        draw_graph: false,
        draw_attention: false,
        ..RenderOptions::default()
    };
    on.data() != render_frame(trace, last, &off).data()
}

#[test]
fn a_graph_brain_on_a_psa_is_recorded_drawn_and_replayed() {
    let trace = trace("graph");
    let units = 11; // a small PSA: 10 masses and the gas
    let neurons = trace.channel(channels::GRAPH_NEURONS.name).expect("neurons recorded");
    // the initial graph: 3 sensing neurons and an actuator per unit
    assert_eq!(neurons.rows().count(), 4 * units);
    let outputs = trace.channel(channels::GRAPH_OUTPUTS.name).expect("outputs recorded");
    assert_eq!(outputs.width, 4 * units);
    assert_eq!(outputs.values.len(), trace.len() * 4 * units);
    assert!(drawn(&trace), "the graph layer draws nothing");
    let replay = Replay::from_trace(&trace, &ReplayOptions::default()).unwrap();
    assert_eq!(replay.graph.expect("graph in the replay").neurons.len(), 4 * units);
    assert!(replay.channels.contains_key("graph_outputs"));
}

#[test]
fn an_attention_brain_on_a_psa_is_recorded_drawn_and_replayed() {
    let trace = trace("attention");
    let units = 11;
    assert_eq!(trace.fixed_values(channels::ATTENTION_SIDE.name), [3.0]);
    let attention = trace.channel(channels::ATTENTION.name).expect("attention recorded");
    assert_eq!(attention.width, units * 9);
    assert!(drawn(&trace), "the attention layer draws nothing");
    let replay = Replay::from_trace(&trace, &ReplayOptions::default()).unwrap();
    assert_eq!(replay.body.attention_side, 3);
    assert_eq!(replay.channels["attention"].per_frame, units * 9);
    // brain unit i (mass i) is drawn on polygon i + 1, the gas unit on the membrane, polygon 0
    let polygons: Vec<f64> = (1..=10).chain([0]).map(f64::from).collect();
    assert_eq!(trace.fixed_values(channels::UNIT_POLYGONS.name), polygons);
    // the plastic weights are for observers, not traces
    assert!(!trace.has(channels::PLASTIC_WEIGHTS.name));
}
