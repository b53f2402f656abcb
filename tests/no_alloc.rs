//! `step` and `Simulation::advance` allocate nothing after set-up (style rule 1): a counting
//! global allocator sees zero allocations across many steps of free, tree and loop models,
//! order 2 and 4, with inputs, springs and dampers.

mod common;
use common::*;
use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use triad::mechanics::step;

struct Counting;

thread_local! {
    // allocations made by this thread (other test-harness threads do not count)
    static ALLOCS: Cell<usize> = const { Cell::new(0) };
}

fn count() -> usize {
    ALLOCS.with(Cell::get)
}

fn bump() {
    let _ = ALLOCS.try_with(|c| c.set(c.get() + 1));
}

// SAFETY-free wrapper: forwards to the system allocator and counts.
#[allow(unsafe_code)]
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        bump();
        // SAFETY: same contract as the caller's.
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: same contract as the caller's.
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new: usize) -> *mut u8 {
        bump();
        // SAFETY: same contract as the caller's.
        unsafe { System.realloc(ptr, layout, new) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

#[test]
fn step_does_not_allocate() {
    let mut b7 = double_pendulum();
    b7.joints[1].actuated = true;
    b7.joints[1].stiffness = 3.0;
    b7.joints[1].damping = 0.2;
    let mut fb = four_bar(1.0, 3.0);
    fb.joints[0].actuated = true;
    fb.joints[1].damping = 0.1;
    for (def, order) in [
        (b7.clone(), 2),
        (b7, 4),
        (heavy_top(), 4),
        (chain(10), 2),
        (fb, 4),
        // a loop between bodies not adjacent in the tree, with a spring and a damper
        (chain_loop(10, Some(2), 5.0, 0.1), 2),
    ] {
        let (m, mut s) = build(&def, settings(0.01, order));
        if !s.inputs().is_empty() {
            s.inputs_mut()[0] = 0.5;
        }
        step(&m, &mut s, 0.01).unwrap();
        let before = count();
        for _ in 0..50 {
            step(&m, &mut s, 0.01).unwrap();
        }
        let n = count() - before;
        assert_eq!(n, 0, "{n} allocations in 50 steps");
    }
}

/// The FMU's and `simulate`'s path allocates nothing either: `Simulation::advance` with its
/// roll-back copy, the check of the outputs, several sub-steps, a carried tiny step.
#[test]
fn simulation_advance_does_not_allocate() {
    let mut def = double_pendulum();
    def.joints[1].actuated = true;
    let mut sim = triad::sim::Simulation::new(&def, settings(0.01, 2), 0.0).unwrap();
    sim.state_mut().inputs_mut()[0] = 0.5;
    sim.advance(0.01).unwrap();
    sim.advance(0.03).unwrap();
    let before = count();
    for k in 0..50 {
        let h = [0.01, 0.03, 1e-12][k % 3];
        sim.advance(h).unwrap();
    }
    let n = count() - before;
    assert_eq!(n, 0, "{n} allocations in 50 communication steps");
}
