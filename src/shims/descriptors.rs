//! Small integer names for objects, as legacy APIs hand them out: Starbase
//! file descriptors (`fildes`) and IRIS GL window identifiers.
//!
//! Numbers are never reused within a process, so a closed descriptor stays
//! invalid instead of silently naming a newer object.

use std::collections::BTreeMap;

use crate::error::{Error, Result};

/// A table of objects named by positive integers.
#[derive(Debug)]
pub struct Descriptors<T> {
    next: i32,
    entries: BTreeMap<i32, T>,
}

impl<T> Descriptors<T> {
    /// An empty table whose first descriptor is `first` (> 0).
    pub const fn new(first: i32) -> Self {
        Descriptors {
            next: first,
            entries: BTreeMap::new(),
        }
    }

    /// Adds `value` under a new descriptor.
    pub fn insert(&mut self, value: T) -> Result<i32> {
        let id = self.next;
        self.next = id.checked_add(1).ok_or_else(|| {
            Error::OutOfMemory("no descriptor numbers left in this process".into())
        })?;
        self.entries.insert(id, value);
        Ok(id)
    }

    /// The object named `id`, if it is live.
    pub fn get(&self, id: i32) -> Option<&T> {
        self.entries.get(&id)
    }

    /// The object named `id`, mutably.
    pub fn get_mut(&mut self, id: i32) -> Option<&mut T> {
        self.entries.get_mut(&id)
    }

    /// Removes and returns the object named `id`.
    pub fn remove(&mut self, id: i32) -> Option<T> {
        self.entries.remove(&id)
    }

    /// The first descriptor whose object satisfies `pred`.
    pub fn find(&self, mut pred: impl FnMut(&T) -> bool) -> Option<i32> {
        self.entries
            .iter()
            .find_map(|(&id, v)| pred(v).then_some(id))
    }

    /// Every live descriptor and its object, in ascending order.
    pub fn iter(&self) -> impl Iterator<Item = (i32, &T)> {
        self.entries.iter().map(|(&id, v)| (id, v))
    }

    /// Drops every entry for which `keep` is false.
    pub fn retain(&mut self, mut keep: impl FnMut(&T) -> bool) {
        self.entries.retain(|_, v| keep(v));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn descriptors_count_up_from_the_first_and_are_never_reused() {
        let mut t = Descriptors::new(3);
        let a = t.insert("a").unwrap();
        let b = t.insert("b").unwrap();
        assert_eq!((a, b), (3, 4));
        assert_eq!(t.remove(a), Some("a"));
        assert_eq!(t.get(a), None, "a closed descriptor names nothing");
        let c = t.insert("c").unwrap();
        assert_eq!(c, 5, "3 is not handed out again");
        assert_eq!(t.find(|v| *v == "c"), Some(5));
        assert_eq!(t.find(|v| *v == "a"), None);
        t.retain(|v| *v != "b");
        assert_eq!(t.iter().map(|(id, _)| id).collect::<Vec<_>>(), vec![5]);
    }

    #[test]
    fn an_exhausted_table_says_so() {
        let mut t = Descriptors::new(i32::MAX);
        assert!(matches!(t.insert(1), Err(Error::OutOfMemory(_))));
        assert_eq!(t.get(i32::MAX), None, "nothing changed");
    }
}
