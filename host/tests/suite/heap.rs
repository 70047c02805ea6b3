//! The test binary's global allocator: `System`, counted per thread (tests
//! run in parallel threads; each sees only its own counts).
//!
//! - [`counted`]: the heap events (`alloc`, `alloc_zeroed`, `realloc`,
//!   `dealloc`) a closure caused.
//! - [`reset_peak`], [`peak`]: the most bytes live at once since a point.

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;

thread_local! {
    static EVENTS: Cell<usize> = const { Cell::new(0) };
    static LIVE: Cell<usize> = const { Cell::new(0) };
    static PEAK: Cell<usize> = const { Cell::new(0) };
}

struct Counting;

// `try_with` throughout: the allocator may run while the thread's locals
// are torn down; those events are of no test's concern.
fn event() {
    let _ = EVENTS.try_with(|c| c.set(c.get() + 1));
}

fn add(n: usize) {
    let _ = LIVE.try_with(|l| {
        let now = l.get() + n;
        l.set(now);
        let _ = PEAK.try_with(|p| p.set(p.get().max(now)));
    });
}

fn sub(n: usize) {
    let _ = LIVE.try_with(|l| l.set(l.get().saturating_sub(n)));
}

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        event();
        add(layout.size());
        unsafe { System.alloc(layout) }
    }
    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        event();
        add(layout.size());
        unsafe { System.alloc_zeroed(layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new: usize) -> *mut u8 {
        event();
        // Counted as a new block beside the old one, as a moving
        // reallocation holds both.
        add(new);
        let p = unsafe { System.realloc(ptr, layout, new) };
        sub(layout.size());
        p
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        event();
        sub(layout.size());
        unsafe { System.dealloc(ptr, layout) }
    }
}

#[global_allocator]
static HEAP: Counting = Counting;

/// Runs `f` and returns its result with the number of heap events it
/// caused on this thread.
pub fn counted<R>(f: impl FnOnce() -> R) -> (R, usize) {
    let before = EVENTS.with(Cell::get);
    let r = f();
    let after = EVENTS.with(Cell::get);
    (r, after - before)
}

/// Starts a measurement: the peak is set to what is live now, which is
/// returned.
pub fn reset_peak() -> usize {
    let live = LIVE.with(Cell::get);
    PEAK.with(|p| p.set(live));
    live
}

/// The most bytes live at once on this thread since [`reset_peak`].
pub fn peak() -> usize {
    PEAK.with(Cell::get)
}
