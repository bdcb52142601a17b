//! Thread pools for the `threads` argument.

use std::collections::HashMap;
use std::sync::{Arc, Mutex, OnceLock};

use pyo3::PyResult;

use crate::errors::value_error;

/// Thread pools by size (0: rayon's global pool, all cores).
pub(crate) fn with_threads<T: Send>(threads: usize, f: impl FnOnce() -> T + Send) -> PyResult<T> {
    static POOLS: OnceLock<Mutex<HashMap<usize, Arc<rayon::ThreadPool>>>> = OnceLock::new();
    if threads == 0 {
        return Ok(f());
    }
    let pool = {
        let mut pools = POOLS
            .get_or_init(|| Mutex::new(HashMap::new()))
            .lock()
            .map_err(|_| value_error("thread pool cache poisoned"))?;
        match pools.get(&threads) {
            Some(p) => Arc::clone(p),
            None => {
                let p = Arc::new(
                    rayon::ThreadPoolBuilder::new()
                        .num_threads(threads)
                        .build()
                        .map_err(value_error)?,
                );
                pools.insert(threads, Arc::clone(&p));
                p
            }
        }
    };
    Ok(pool.install(f))
}
