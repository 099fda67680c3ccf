//! `threads::pin_global_pool` keeps each worker of rayon's global pool on one processor:
//! on Linux with two processors or more, every worker may run on exactly one, and the
//! workers cover the processors in turn. (A test binary of its own: the global pool is
//! the process's.)

#[cfg(target_os = "linux")]
#[test]
fn each_pool_thread_is_kept_on_one_processor_in_turn() {
    use rustix::thread::{CpuSet, sched_getaffinity};
    let allowed: Vec<usize> = {
        let set = sched_getaffinity(None).expect("the test's own processors");
        (0..CpuSet::MAX_CPU).filter(|&c| set.is_set(c)).collect()
    };
    // (Set to 0 around this test, pinning would be off: the test says what it checks.)
    assert!(
        std::env::var("SHATTER_PIN_THREADS").is_err(),
        "run without SHATTER_PIN_THREADS"
    );
    let spread = shatter_lab::threads::pin_global_pool().expect("no bad variable");
    let per_worker: Vec<(usize, Vec<usize>)> = rayon::broadcast(|ctx| {
        let set = sched_getaffinity(None).expect("a worker's processors");
        let cpus = (0..CpuSet::MAX_CPU).filter(|&c| set.is_set(c)).collect();
        (ctx.index(), cpus)
    });
    if allowed.len() < 2 {
        assert_eq!(spread, 0);
        return;
    }
    assert_eq!(spread, allowed.len());
    for (i, cpus) in &per_worker {
        assert_eq!(cpus, &vec![allowed[i % allowed.len()]], "worker {i}");
    }
    // The main thread is left where it may run.
    let main = sched_getaffinity(None).expect("the test's own processors");
    assert_eq!(
        (0..CpuSet::MAX_CPU).filter(|&c| main.is_set(c)).count(),
        allowed.len()
    );
}
