//! Large arrays backed by transparent huge pages (Linux), and prefetch hints.
//!
//! At N = 10⁶ the engine's arrays span ~130 MB and every event lands at a random
//! place in them; with 4 KiB pages nearly every access also misses the TLB, with
//! 2 MiB pages a few dozen TLB entries cover the state. Many kernels hand out huge
//! pages only to memory marked with `madvise(MADV_HUGEPAGE)`, so large arrays are
//! allocated here and marked (rounded inward to whole 2 MiB pages) before they are
//! first written. Nothing about the values changes: this is a hint about how to
//! map memory. [`prefetch`] is the other hint: start loading a cache line the next
//! events will need. See docs/performance.md, "memory".

/// Arrays smaller than this are left alone (they cannot fill a huge page).
const HUGE_PAGE: usize = 2 << 20;

/// An empty vector with room for `capacity` elements, its memory marked for huge
/// pages when it is large enough.
pub(crate) fn with_capacity<T>(capacity: usize) -> Vec<T> {
    let v = Vec::with_capacity(capacity);
    advise_huge_pages(&v);
    v
}

/// `n` copies of `value` in memory marked for huge pages.
pub(crate) fn filled<T: Clone>(n: usize, value: T) -> Vec<T> {
    let mut v = with_capacity(n);
    v.resize(n, value);
    v
}

/// The items of `items` (exactly `n` of them) in memory marked for huge pages.
pub(crate) fn collect<T>(n: usize, items: impl IntoIterator<Item = T>) -> Vec<T> {
    let mut v = with_capacity(n);
    v.extend(items);
    v
}

/// Mark the whole 2 MiB pages inside `v`'s allocation for transparent huge pages.
#[cfg(target_os = "linux")]
fn advise_huge_pages<T>(v: &Vec<T>) {
    let bytes = v.capacity() * std::mem::size_of::<T>();
    let start = v.as_ptr() as usize;
    let lo = start.next_multiple_of(HUGE_PAGE);
    let hi = (start + bytes) / HUGE_PAGE * HUGE_PAGE;
    if hi <= lo {
        return;
    }
    // SAFETY: [lo, hi) lies inside the live allocation owned by `v` (rounded inward
    // to 2 MiB boundaries, so it is page-aligned as madvise requires). MADV_HUGEPAGE
    // only changes how the kernel may back these pages; it never changes their
    // contents, frees them or alters the mapping's permissions, so no Rust reference
    // or value is affected. A failure (e.g. THP compiled out) is harmless and ignored.
    unsafe {
        libc::madvise(lo as *mut libc::c_void, hi - lo, libc::MADV_HUGEPAGE);
    }
}

/// Huge pages are a Linux hint; elsewhere memory stays as the allocator gives it.
#[cfg(not(target_os = "linux"))]
fn advise_huge_pages<T>(_v: &Vec<T>) {}

/// Ask the processor to start loading the cache line holding `x`, without waiting for
/// it: a hint that lets the loads of the next events overlap the current one. A plain
/// read would do the same but, on a cache miss, hold up the processor until the line
/// arrives.
#[inline(always)]
pub(crate) fn prefetch<T>(x: &T) {
    prefetch_ptr(x as *const T);
}

/// [`prefetch`] of element `i` of `v`, without a bounds check: an index past the end
/// only names an address nobody reads, and a prefetch of any address is harmless.
/// For the look-ahead, where bounds checks were a large share of its instructions.
#[inline(always)]
pub(crate) fn prefetch_at<T>(v: &[T], i: usize) {
    prefetch_ptr(v.as_ptr().wrapping_add(i));
}

/// [`prefetch`] of the cache line holding address `x`, which need not point into
/// any allocation.
#[inline(always)]
fn prefetch_ptr<T>(x: *const T) {
    #[cfg(target_arch = "x86_64")]
    // SAFETY: `_mm_prefetch` is `unsafe` only because it is declared for the SSE
    // target feature, which every x86_64 processor has (it is part of the baseline
    // the standard library itself is compiled for). A prefetch never faults and
    // changes no memory or register visible to the program, whatever the address
    // (even one outside any allocation): nothing is dereferenced.
    unsafe {
        use std::arch::x86_64::{_mm_prefetch, _MM_HINT_T0};
        _mm_prefetch::<_MM_HINT_T0>(x as *const i8);
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = x;
}
