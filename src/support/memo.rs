//! A process-wide table of results worth computing once (decoders' proven bounds, specs'
//! error statistics), which a store that outlives the process (the CLI's figure cache)
//! can export and import.

use std::collections::BTreeMap;
use std::sync::Mutex;

/// Results by key, shared by every thread. Ordered, so that an export is deterministic.
pub(crate) struct Memo<K, V>(Mutex<BTreeMap<K, V>>);

impl<K: Ord + Clone, V: Clone> Memo<K, V> {
    pub const fn new() -> Self {
        Memo(Mutex::new(BTreeMap::new()))
    }

    fn lock(&self) -> std::sync::MutexGuard<'_, BTreeMap<K, V>> {
        // A panic elsewhere cannot leave a half-written entry: entries are inserted
        // whole, and an interrupted extend leaves only whole entries.
        self.0.lock().unwrap_or_else(|e| e.into_inner())
    }

    pub fn get(&self, k: &K) -> Option<V> {
        self.lock().get(k).cloned()
    }

    pub fn contains(&self, k: &K) -> bool {
        self.lock().contains_key(k)
    }

    pub fn extend(&self, entries: impl IntoIterator<Item = (K, V)>) {
        self.lock().extend(entries)
    }

    /// Every entry, in key order.
    pub fn export(&self) -> Vec<(K, V)> {
        self.lock()
            .iter()
            .map(|(k, v)| (k.clone(), v.clone()))
            .collect()
    }
}
