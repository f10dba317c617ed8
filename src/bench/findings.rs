//! The findings of the paper's section 6, each checked on the run's numbers: holds, does not
//! hold, or not measured (a combination it needs was not planned). Delivery times are compared on
//! the requests both methods deliver ("common"), since means over different delivered sets
//! compare different requests; execution times are machine-dependent.

use super::summary::{rows_of, total};
use super::{BenchData, MethodSummary};
use crate::compose::{PlanOptions, RouteMethod};
use crate::eaas::SharingPolicy;
use crate::precompose::Positioning;
use serde::Serialize;
use std::collections::BTreeMap;
use Positioning::{EnergyAware as Ea, LocationAware as La};
use RouteMethod::{Dijkstra, FloydWarshall, Sequential};
use SharingPolicy::{Fb, None as NoSharing, Pb};

/// Whether a finding holds on the run.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Verdict {
    /// The run's numbers agree with the paper's claim.
    Holds,
    /// They do not.
    DoesNotHold,
    /// A combination the finding needs was not planned.
    NotMeasured,
}

impl std::fmt::Display for Verdict {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.pad(match self {
            Verdict::Holds => "holds",
            Verdict::DoesNotHold => "does not hold",
            Verdict::NotMeasured => "not measured",
        })
    }
}

/// One finding of the paper, checked.
#[derive(Debug, Clone, Serialize)]
pub struct Finding {
    /// Its number (as in instances/findings-195/README.md).
    pub id: &'static str,
    /// The claim.
    pub claim: &'static str,
    /// The paper's numbers.
    pub paper: &'static str,
    /// The run's numbers.
    pub ours: String,
    /// Holds?
    pub verdict: Verdict,
    /// The figure showing it, relative to the output directory.
    pub figure: &'static str,
}

fn combo(sharing: SharingPolicy, positioning: Positioning, route: RouteMethod) -> PlanOptions {
    PlanOptions {
        sharing,
        positioning,
        route,
        support: None,
    }
}

/// Delivered counts (delivered, requests) of a combination, if planned.
fn delivered(methods: &[MethodSummary], o: &PlanOptions) -> Option<(usize, usize)> {
    methods
        .iter()
        .find(|m| {
            (m.options.sharing, m.options.positioning, m.options.route)
                == (o.sharing, o.positioning, o.route)
        })
        .map(|m| (m.delivered, m.requests))
}

/// On the requests both combinations deliver: their count and the two mean delivery times.
fn common(data: &BenchData, a: &PlanOptions, b: &PlanOptions) -> Option<(usize, f64, f64)> {
    let (ra, rb) = (rows_of(data, a), rows_of(data, b));
    if ra.is_empty() || rb.is_empty() {
        return None;
    }
    let dt: BTreeMap<usize, f64> = ra
        .iter()
        .filter(|r| r.success)
        .map(|r| (r.request_index, r.dt_min))
        .collect();
    let pairs: Vec<(f64, f64)> = rb
        .iter()
        .filter(|r| r.success)
        .filter_map(|r| dt.get(&r.request_index).map(|&x| (x, r.dt_min)))
        .collect();
    let n = pairs.len().max(1) as f64;
    Some((
        pairs.len(),
        total(pairs.iter().map(|p| p.0)) / n,
        total(pairs.iter().map(|p| p.1)) / n,
    ))
}

/// Total execution time of a combination, ms.
fn exec_ms(methods: &[MethodSummary], o: &PlanOptions) -> Option<f64> {
    methods
        .iter()
        .find(|m| {
            (m.options.sharing, m.options.positioning, m.options.route)
                == (o.sharing, o.positioning, o.route)
        })
        .map(|m| m.exec_ms_total)
}

fn verdict(measured: bool, holds: bool) -> Verdict {
    match (measured, holds) {
        (false, _) => Verdict::NotMeasured,
        (true, true) => Verdict::Holds,
        (true, false) => Verdict::DoesNotHold,
    }
}

fn count((d, n): (usize, usize)) -> String {
    format!("{d} / {n}")
}

/// The findings of section 6 on the run: `methods` are its summaries, `data` its rows.
pub fn findings(methods: &[MethodSummary], data: &BenchData) -> Vec<Finding> {
    let base = combo(NoSharing, La, Sequential);
    let sharing = [
        combo(Pb, La, Sequential),
        combo(Fb, La, Sequential),
        combo(Pb, Ea, Sequential),
        combo(Fb, Ea, Sequential),
    ];
    vec![
        sharing_delivers_more(methods, &base, &sharing),
        sharing_delivers_faster(data, &base, &sharing),
        location_aware_delivers_more(methods, &sharing),
        energy_aware_delivers_faster(data, &sharing),
        pb_delivers_faster_than_fb(data, &sharing),
        pb_plans_faster_than_fb(methods, &sharing),
        shortest_paths_deliver_fewer(methods, &base),
    ]
}

/// 1a: sharing delivers more requests than the baseline. `sharing`: PB-LA, FB-LA, PB-EA, FB-EA.
fn sharing_delivers_more(
    methods: &[MethodSummary],
    base: &PlanOptions,
    sharing: &[PlanOptions; 4],
) -> Finding {
    let names = ["PB-LA", "FB-LA", "PB-EA", "FB-EA"];
    let b = delivered(methods, base);
    let s: Vec<Option<(usize, usize)>> = sharing.iter().map(|o| delivered(methods, o)).collect();
    let measured = b.is_some() && s.iter().all(Option::is_some);
    let holds = measured && s.iter().all(|x| x.unwrap().0 > b.unwrap().0);
    Finding {
        id: "1a",
        claim: "sharing delivers more requests than the no-sharing baseline (Algorithm 1)",
        paper: "baseline 8,839 / 10,000, below each of PB and FB under both placements",
        ours: if measured {
            format!(
                "baseline {}; {}",
                count(b.unwrap()),
                names
                    .iter()
                    .zip(&s)
                    .map(|(n, x)| format!("{n} {}", count(x.unwrap())))
                    .collect::<Vec<_>>()
                    .join(", ")
            )
        } else {
            String::new()
        },
        verdict: verdict(measured, holds),
        figure: "figures/delivered.svg",
    }
}

/// 1b: sharing delivers faster than the baseline (energy-aware placement).
fn sharing_delivers_faster(
    data: &BenchData,
    base: &PlanOptions,
    sharing: &[PlanOptions; 4],
) -> Finding {
    let c = common(data, base, &sharing[2]);
    Finding {
        id: "1b",
        claim: "sharing delivers faster than the baseline (energy-aware placement)",
        paper: "figure only: PB and FB below the baseline's delivery time",
        ours: c.map_or(String::new(), |(n, a, b)| {
            format!(
                "common to baseline and PB-EA ({n}): dt {a:.1} (baseline) vs {b:.1} min (PB-EA)"
            )
        }),
        verdict: verdict(c.is_some_and(|c| c.0 > 0), c.is_some_and(|(_, a, b)| b < a)),
        figure: "figures/dt-by-distance-energy-aware.svg",
    }
}

/// 2: location-aware delivers more requests (PB + FB).
fn location_aware_delivers_more(methods: &[MethodSummary], sharing: &[PlanOptions; 4]) -> Finding {
    let la = [&sharing[0], &sharing[1]].map(|o| delivered(methods, o));
    let ea = [&sharing[2], &sharing[3]].map(|o| delivered(methods, o));
    let measured = la.iter().chain(&ea).all(Option::is_some);
    let sum = |x: [Option<(usize, usize)>; 2]| {
        x.iter()
            .flatten()
            .fold((0, 0), |acc, v| (acc.0 + v.0, acc.1 + v.1))
    };
    let (sla, sea) = (sum(la), sum(ea));
    Finding {
        id: "2",
        claim: "location-aware placement delivers more requests than energy-aware (PB + FB)",
        paper: "19,271 / 20,000 vs 18,050 / 20,000",
        ours: if measured {
            format!(
                "location-aware {} vs energy-aware {}",
                count(sla),
                count(sea)
            )
        } else {
            String::new()
        },
        verdict: verdict(measured, sla.0 > sea.0),
        figure: "figures/delivered.svg",
    }
}

/// 3: energy-aware placement gives shorter delivery times (common requests).
fn energy_aware_delivers_faster(data: &BenchData, sharing: &[PlanOptions; 4]) -> Finding {
    let cp = common(data, &sharing[0], &sharing[2]);
    let cf = common(data, &sharing[1], &sharing[3]);
    let measured = cp.is_some_and(|c| c.0 > 0) && cf.is_some_and(|c| c.0 > 0);
    Finding {
        id: "3",
        claim: "energy-aware placement gives shorter delivery times than location-aware",
        paper: "figure only",
        ours: if measured {
            let ((np, lp, ep), (nf, lf, ef)) = (cp.unwrap(), cf.unwrap());
            format!(
                "common PB ({np}): {ep:.1} (EA) vs {lp:.1} min (LA); common FB ({nf}): {ef:.1} vs {lf:.1}"
            )
        } else {
            String::new()
        },
        verdict: verdict(
            measured,
            measured && cp.unwrap().2 < cp.unwrap().1 && cf.unwrap().2 < cf.unwrap().1,
        ),
        figure: "figures/dt-by-distance-energy-aware.svg",
    }
}

/// 4a: PB beats FB on delivery time (common requests).
fn pb_delivers_faster_than_fb(data: &BenchData, sharing: &[PlanOptions; 4]) -> Finding {
    let c_la = common(data, &sharing[0], &sharing[1]);
    let c_ea = common(data, &sharing[2], &sharing[3]);
    let measured = c_la.is_some_and(|c| c.0 > 0) && c_ea.is_some_and(|c| c.0 > 0);
    Finding {
        id: "4a",
        claim: "PB gives shorter delivery times than FB",
        paper: "figure only",
        ours: if measured {
            let ((na, pa, fa), (ne, pe, fe)) = (c_la.unwrap(), c_ea.unwrap());
            format!(
                "common LA ({na}): {pa:.1} (PB) vs {fa:.1} min (FB); common EA ({ne}): {pe:.1} vs {fe:.1}"
            )
        } else {
            String::new()
        },
        verdict: verdict(
            measured,
            measured && c_la.unwrap().1 < c_la.unwrap().2 && c_ea.unwrap().1 < c_ea.unwrap().2,
        ),
        figure: "figures/dt-by-distance-location-aware.svg",
    }
}

/// 4b: PB beats FB on execution time (machine-dependent).
fn pb_plans_faster_than_fb(methods: &[MethodSummary], sharing: &[PlanOptions; 4]) -> Finding {
    let t: Vec<Option<f64>> = sharing.iter().map(|o| exec_ms(methods, o)).collect();
    let measured = t.iter().all(Option::is_some);
    let t: Vec<f64> = t.into_iter().flatten().collect();
    Finding {
        id: "4b",
        claim: "PB plans faster than FB (execution time; machine-dependent)",
        paper: "figure only",
        ours: if measured {
            format!(
                "total planning time, s: PB-LA {:.2} vs FB-LA {:.2}, PB-EA {:.2} vs FB-EA {:.2}",
                t[0] / 1e3,
                t[1] / 1e3,
                t[2] / 1e3,
                t[3] / 1e3
            )
        } else {
            String::new()
        },
        verdict: verdict(measured, measured && t[0] < t[1] && t[2] < t[3]),
        figure: "figures/exec-time.svg",
    }
}

/// 5: Dijkstra and Floyd–Warshall deliver fewer than Algorithm 1 (no sharing).
fn shortest_paths_deliver_fewer(methods: &[MethodSummary], base: &PlanOptions) -> Finding {
    let b = delivered(methods, base);
    let d = delivered(methods, &combo(NoSharing, La, Dijkstra));
    let f = delivered(methods, &combo(NoSharing, La, FloydWarshall));
    let measured = b.is_some() && d.is_some() && f.is_some();
    Finding {
        id: "5",
        claim: "Dijkstra and Floyd–Warshall deliver fewer requests than Algorithm 1",
        paper: "Dijkstra 6,646, Floyd–Warshall 6,691 vs Algorithm 1 8,839 / 10,000",
        ours: if measured {
            format!(
                "no sharing: Dijkstra {}, Floyd–Warshall {} vs Algorithm 1 {}",
                count(d.unwrap()),
                count(f.unwrap()),
                count(b.unwrap())
            )
        } else {
            String::new()
        },
        verdict: verdict(
            measured,
            measured && d.unwrap().0 < b.unwrap().0 && f.unwrap().0 < b.unwrap().0,
        ),
        figure: "figures/delivered.svg",
    }
}
