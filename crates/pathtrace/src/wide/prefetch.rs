//! A hint to the caches: ask for the lines of a value before it is read. Lane loops read one
//! address per lane from tables larger than the L2 cache (an environment map's texels and its
//! sampling rows); asked for lane by lane before any is read, the lanes' misses are served
//! together instead of one after another. The BVH walks ask for a node when they push it.

/// Bytes per cache line on the x86-64 CPUs this targets.
const LINE: usize = 64;

/// Asks the caches for every line `items` touches (its first byte's, one per 64 bytes after,
/// and its last byte's). A hint only: it reads nothing into the program, never faults and
/// changes no value; on other targets it does nothing.
#[inline(always)]
pub fn prefetch<T>(items: &[T]) {
    #[cfg(target_arch = "x86_64")]
    {
        use std::arch::x86_64::{_mm_prefetch, _MM_HINT_T0};
        let bytes = std::mem::size_of_val(items);
        let first: *const i8 = items.as_ptr().cast();
        let mut offset = 0;
        while offset < bytes {
            // SAFETY: a prefetch never faults, whatever the address, and reads nothing into the
            // program; the addresses lie inside `items`. Allowed for the measured gains recorded
            // in docs/benchmarks.md (issue 14).
            #[allow(unsafe_code)]
            unsafe {
                _mm_prefetch::<_MM_HINT_T0>(first.wrapping_add(offset));
            }
            offset += LINE;
        }
        // The last byte's line: the lines above start from the first byte, so a value that is
        // not whole lines at a line's start may end in one they do not reach.
        let whole_lines = bytes.is_multiple_of(LINE) && std::mem::align_of::<T>().is_multiple_of(LINE);
        if bytes > 0 && !whole_lines {
            // SAFETY: as above; `bytes - 1` is inside `items`.
            #[allow(unsafe_code)]
            unsafe {
                _mm_prefetch::<_MM_HINT_T0>(first.wrapping_add(bytes - 1));
            }
        }
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = items;
}
