//! Controllers allocate nothing in `control`: everything is preallocated by `BrainSpec::build`.
//! A counting global allocator (this test binary only) counts allocations on the test's thread.

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use vsrlab_body::Morphology;
use vsrlab_brain::BrainShape;
use vsrlab_brain::BrainSpec;

struct Counting;

thread_local! {
    static ALLOCATIONS: Cell<usize> = const { Cell::new(0) };
}

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let _ = ALLOCATIONS.try_with(|c| c.set(c.get() + 1));
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        let _ = ALLOCATIONS.try_with(|c| c.set(c.get() + 1));
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

fn allocations() -> usize {
    ALLOCATIONS.with(|c| c.get())
}

#[test]
fn control_does_not_allocate() {
    let before = allocations();
    std::hint::black_box(vec![1u8; 16]);
    assert!(allocations() > before, "the counter counts");

    let m = Morphology::named("biped-4x3").unwrap();
    let rpv = vec![4; m.voxel_count()];
    for form in [
        "phase",
        "constant:0.5",
        "random:0.1",
        "phase-grid:freq",
        "mlp",
        "mlp:16,8",
        "distributed-mlp",
        "distributed-mlp-hetero:2",
        "step:0.33:distributed-mlp",
        "smoothed:3:mlp",
        "hebbian",
        "hebbian:incoming",
        "hebbian:dew",
        "hebbian:l2",
        "attention",
        "attention:hetero",
        "attention:slow",
        "step:0.33:attention",
        "local-mlp",
        "local-mlp:1",
        "graph",
    ] {
        let spec = BrainSpec::parse(form)
            .unwrap()
            .with_random_parameters(1, &BrainShape::grid(&m, &rpv))
            .unwrap();
        let mut brain = spec.build(&BrainShape::grid(&m, &rpv)).unwrap();
        brain.reset();
        let readings = vec![0.3; 40];
        let mut actuations = vec![0.0; m.voxel_count()];
        // the first call may size lazily-grown buffers (the random baseline does)
        brain.control(1.0 / 60.0, &readings, &mut actuations);
        let before = allocations();
        for k in 2..=600 {
            brain.control(k as f64 / 60.0, &readings, &mut actuations);
        }
        assert_eq!(allocations() - before, 0, "{form} allocated in control");
    }
}
