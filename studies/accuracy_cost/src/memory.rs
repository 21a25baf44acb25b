//! Heap bytes held: a counting global allocator.
//!
//! [`HeapCounter`] forwards every request to [`System`] and keeps two tallies
//! of the bytes currently allocated (requested sizes, not the allocator's
//! rounding or bookkeeping):
//!
//! - a process-wide one ([`live_bytes`]), which counts **all threads**;
//! - one per thread ([`thread_live_bytes`]): what the calling thread has
//!   allocated minus what it has freed (it can go negative on a thread that
//!   frees memory another thread allocated).
//!
//! [`held_by`] measures what a built value keeps with the per-thread tally,
//! so other threads (tests running in parallel) do not disturb it; the build
//! must therefore allocate on the calling thread (tessellation and parry's
//! `TriMesh` do; a build that hands work to a thread pool would be
//! undercounted). For the study, measure on one thread with nothing else
//! running; then both tallies agree.
//!
//! The binary enables it with
//! `#[global_allocator] static HEAP: memory::HeapCounter = memory::HeapCounter;`;
//! without that line every figure here is zero.

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use std::sync::atomic::{AtomicUsize, Ordering};

/// A global allocator that forwards to [`System`] and counts live heap bytes.
pub struct HeapCounter;

/// Bytes currently allocated through [`HeapCounter`], all threads.
static LIVE: AtomicUsize = AtomicUsize::new(0);

thread_local! {
    // `const` initialisation and no destructor: touching it never allocates
    // or registers anything, so the allocator may use it.
    static THREAD_LIVE: Cell<isize> = const { Cell::new(0) };
}

fn added(bytes: usize) {
    LIVE.fetch_add(bytes, Ordering::Relaxed);
    // `try_with`: during thread teardown the slot may be gone; the global
    // tally still counts.
    let _ = THREAD_LIVE.try_with(|c| c.set(c.get().wrapping_add(bytes as isize)));
}

fn removed(bytes: usize) {
    LIVE.fetch_sub(bytes, Ordering::Relaxed);
    let _ = THREAD_LIVE.try_with(|c| c.set(c.get().wrapping_sub(bytes as isize)));
}

// SAFETY: every method forwards to `System` with the caller's arguments
// unchanged, so `System`'s guarantees carry over; the counting only reads
// sizes and touches atomics and a destructor-free thread-local, never the
// memory handed out, and never allocates.
unsafe impl GlobalAlloc for HeapCounter {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        // SAFETY: the caller upholds `GlobalAlloc::alloc`'s contract.
        let p = unsafe { System.alloc(layout) };
        if !p.is_null() {
            added(layout.size());
        }
        p
    }

    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        // SAFETY: the caller upholds `GlobalAlloc::alloc_zeroed`'s contract.
        let p = unsafe { System.alloc_zeroed(layout) };
        if !p.is_null() {
            added(layout.size());
        }
        p
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        // SAFETY: the caller upholds `GlobalAlloc::realloc`'s contract; `ptr`
        // came from this allocator, i.e. from `System`.
        let p = unsafe { System.realloc(ptr, layout, new_size) };
        // On failure the old block stays allocated: nothing changes.
        if !p.is_null() {
            removed(layout.size());
            added(new_size);
        }
        p
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: the caller upholds `GlobalAlloc::dealloc`'s contract; `ptr`
        // came from this allocator, i.e. from `System`.
        unsafe { System.dealloc(ptr, layout) };
        removed(layout.size());
    }
}

/// Heap bytes currently allocated by all threads (zero unless
/// [`HeapCounter`] is the global allocator).
#[cfg_attr(not(test), allow(dead_code))]
pub fn live_bytes() -> usize {
    LIVE.load(Ordering::Relaxed)
}

/// Heap bytes the calling thread has allocated minus those it has freed.
pub fn thread_live_bytes() -> isize {
    THREAD_LIVE.with(Cell::get)
}

/// Runs `build` and returns its value with the heap bytes the value keeps:
/// the calling thread's live bytes after minus before (temporaries freed
/// during the build do not count), saturating at 0. See the module docs for
/// what is and is not counted.
pub fn held_by<T>(build: impl FnOnce() -> T) -> (T, usize) {
    let before = thread_live_bytes();
    let value = build();
    let after = thread_live_bytes();
    (
        value,
        usize::try_from(after.saturating_sub(before)).unwrap_or(0),
    )
}

/// Whether [`HeapCounter`] is the global allocator (an allocation moves the
/// tally).
#[cfg_attr(not(test), allow(dead_code))]
pub fn installed() -> bool {
    let before = thread_live_bytes();
    let probe = std::hint::black_box(Box::new(0u64));
    let counted = thread_live_bytes() != before;
    drop(probe);
    counted
}

/// These tests are meaningful only in a binary that declares
/// `HeapCounter` as its `#[global_allocator]` (the accuracy_cost example and
/// its test build do); elsewhere they fail on purpose at the first assert.
/// Builds a value, timing it and counting the heap it holds:
/// `(value, seconds, bytes)`.
pub fn built<M>(build: impl FnOnce() -> M) -> (M, f64, usize) {
    let start = std::time::Instant::now();
    let (m, bytes) = held_by(build);
    (m, start.elapsed().as_secs_f64(), bytes)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::hint::black_box;

    fn require_counter() {
        assert!(
            installed(),
            "memory::HeapCounter is not the global allocator of this binary"
        );
    }

    #[test]
    fn a_kept_buffer_counts_its_size() {
        require_counter();
        let (v, bytes) = held_by(|| vec![0u8; 1 << 20]);
        assert!(bytes >= 1 << 20, "held {bytes} bytes");
        assert!(bytes < (1 << 20) + 4096, "held {bytes} bytes");
        assert!(live_bytes() >= 1 << 20);
        drop(v);
    }

    #[test]
    fn temporaries_do_not_count() {
        require_counter();
        let (len, bytes) = held_by(|| {
            let v = black_box(vec![1u8; 1 << 20]);
            let w = black_box(vec![2u64; 1000]);
            v.len() + w.len()
        });
        assert_eq!(len, (1 << 20) + 1000);
        assert!(bytes < 1024, "held {bytes} bytes");
    }

    #[test]
    fn growth_by_realloc_is_tracked() {
        require_counter();
        let (v, bytes) = held_by(|| {
            let mut v: Vec<u32> = Vec::with_capacity(4);
            v.extend(0..100_000u32);
            v
        });
        assert_eq!(bytes, v.capacity() * 4, "realloc must adjust the tally");
        let before = thread_live_bytes();
        drop(v);
        assert_eq!(before - thread_live_bytes(), (bytes) as isize);
    }
}
