//! Sizes a user can type are bounded: huge layers, signal counts or parameter totals are
//! refused with the field named, before anything is allocated.

use vsrlab_body::Morphology;
use vsrlab_brain::BrainShape;
use vsrlab_brain::{BrainError, BrainSpec};

fn count(brain: &str, body: &str) -> Result<usize, BrainError> {
    let body = Morphology::parse(body).unwrap();
    let readings = vec![4; body.voxel_count()];
    BrainSpec::parse(brain)?.parameter_count(&BrainShape::grid(&body, &readings))
}

fn field_of(result: Result<usize, BrainError>) -> &'static str {
    match result {
        Err(BrainError::Invalid { field, .. }) => field,
        other => panic!("expected an invalid field, got {other:?}"),
    }
}

#[test]
fn huge_brains_are_refused_naming_the_field() {
    assert_eq!(field_of(count("mlp:100000000", "biped-4x3")), "hidden");
    assert_eq!(field_of(count("mlp:50000,50000", "biped-4x3")), "hidden");
    assert_eq!(field_of(count("distributed-mlp:1000000000", "biped-4x3")), "signals");
    assert_eq!(field_of(count("distributed-mlp-hetero:1000", "box-10x10")), "hidden");
    let body = Morphology::parse("biped-4x3").unwrap();
    let err = BrainSpec::parse("distributed-mlp:100000000000000000")
        .unwrap()
        .build(&BrainShape::grid(&body, &[4; 10]))
        .err()
        .unwrap();
    assert!(err.to_string().contains("signals"), "{err}");
    // the usual sizes are untouched
    assert_eq!(count("mlp", "biped-4x3"), Ok(1336));
    assert_eq!(count("distributed-mlp-hetero", "box-10x10"), Ok(4500));
}
