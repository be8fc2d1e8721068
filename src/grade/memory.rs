//! Memory freed between grading's phases, given back to the system. glibc keeps what a
//! program frees inside its heap (and in each worker thread's own heap) for later use; but a
//! later phase's large blocks come from fresh mappings instead, so the freed pages would stay
//! counted in the process's memory to the end. `malloc_trim` returns every whole free page:
//! a class of all-different answers then needs far less memory (issue 20 §5). Elsewhere
//! (another C library or system) this does nothing.

/// How many different answers make a class of many, where reading gives back the memory
/// its pieces freed as they are joined (each time costs some milliseconds).
pub const MANY: usize = 16 * 1024;

/// Returns the whole free pages of every heap to the system (a few milliseconds).
pub fn give_back() {
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    // SAFETY: malloc_trim only releases memory the allocator holds free; it takes no pointer
    // and may be called at any time from any thread.
    unsafe {
        libc::malloc_trim(0);
    }
}

/// Has every block of 256 KB or more mapped on its own and unmapped when freed. glibc's
/// default raises that threshold to the size of the largest block freed so far, after which
/// the large, short-lived lists of each phase (sorted keys, counts) come from the heap and,
/// freed, stay counted to the end: each phase's lists then added up instead of coming and
/// going (issue 20 §5).
pub fn map_large_blocks() {
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    // SAFETY: mallopt only changes an allocator setting; it takes no pointer. It is called
    // before grading starts its worker threads.
    unsafe {
        libc::mallopt(libc::M_MMAP_THRESHOLD, 256 * 1024);
    }
}
