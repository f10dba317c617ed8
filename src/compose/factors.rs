//! The energy model's leg factors (wind factor and slot factors, [`crate::energy`]) of every
//! directed edge, shared by every request whose swarm flies the same formation slots: they depend
//! on the slots, the heading and the wind, not on the drones' payloads. Each is computed the first
//! time a planner needs it; any thread may fill an entry, and every thread reads the same numbers.

use crate::energy;
use crate::network::Leg;
use crate::problem::{Profile, SkywayGraph, Wind};
use nalgebra::Vector2;
use std::sync::{Arc, Mutex, OnceLock};

/// The factors of one leg: the wind factor and one slot factor per slot.
#[derive(Debug)]
pub(crate) struct LegFactors {
    pub wind_factor: f64,
    pub slot_factors: Vec<f64>,
    /// The least of `slot_factors`.
    pub min_slot_factor: f64,
}

/// The leg factors of every directed edge for one set of formation slots.
#[derive(Debug)]
pub struct EdgeFactors {
    slots_m: Vec<Vector2<f64>>,
    /// Edge `e` flown from its file `from` node at `2 e`, the other way at `2 e + 1`.
    legs: Vec<OnceLock<LegFactors>>,
}

impl EdgeFactors {
    /// The factors of `leg` (directed edge index `key`), computed on first use.
    pub(crate) fn leg(&self, profile: &Profile, key: usize, leg: &Leg) -> &LegFactors {
        self.legs[key].get_or_init(|| {
            let wind = Wind {
                speed_mps: leg.wind_speed_mps,
                from_deg: leg.wind_from_deg,
            };
            let slot_factors = energy::slot_factors(profile, &self.slots_m, leg.heading_deg, &wind);
            LegFactors {
                wind_factor: energy::wind_factor(profile, leg.heading_deg, &wind),
                min_slot_factor: slot_factors.iter().copied().fold(f64::INFINITY, f64::min),
                slot_factors,
            }
        })
    }
}

/// [`EdgeFactors`] per set of formation slots met so far on one network with one profile.
#[derive(Debug)]
pub struct EdgeFactorCache {
    directed_edges: usize,
    tables: Mutex<Vec<Arc<EdgeFactors>>>,
}

impl EdgeFactorCache {
    /// An empty cache for the directed edges of `graph`.
    pub fn new(graph: &SkywayGraph) -> EdgeFactorCache {
        EdgeFactorCache {
            directed_edges: 2 * graph.edge_count(),
            tables: Mutex::new(Vec::new()),
        }
    }

    /// The table of the formation slots `slots_m`, created empty when first asked for.
    ///
    /// # Complexity
    /// O(tables x slots) to find it: one table per swarm size met.
    pub fn for_slots(&self, slots_m: &[Vector2<f64>]) -> Arc<EdgeFactors> {
        // A poisoned lock only means another thread panicked while holding it; the tables are
        // still consistent (an entry is pushed whole).
        let mut tables = self.tables.lock().unwrap_or_else(|e| e.into_inner());
        if let Some(t) = tables.iter().find(|t| t.slots_m == slots_m) {
            return Arc::clone(t);
        }
        let table = Arc::new(EdgeFactors {
            slots_m: slots_m.to_vec(),
            legs: (0..self.directed_edges).map(|_| OnceLock::new()).collect(),
        });
        tables.push(Arc::clone(&table));
        table
    }
}
