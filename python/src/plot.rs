//! `swarmplan.plot`, `Instance.plot` and `Plan._repr_svg_`: the figure of a plan, or of two
//! plans of the same request side by side, as the SVG text `swarmplan plot` writes for them
//! (the core's [`plans_svg`]: the same checks, the same bytes).

use pyo3::prelude::*;
use swarmplan::compose::RequestReport;
use swarmplan::plot::data::BatteryUnit;
use swarmplan::plot::draw::plans_svg;

use crate::errors::to_py_err;
use crate::instance::InstanceData;
use crate::results::{read_plan, Plan};

/// The SVG of `plan` (and `compare`, each a `Plan`, its dict or its JSON text) drawn on the
/// instance `on`.
pub(crate) fn svg_on(
    py: Python<'_>,
    on: &InstanceData,
    plan: &Bound<'_, PyAny>,
    compare: Option<&Bound<'_, PyAny>>,
    percent: bool,
) -> PyResult<String> {
    let mut reports = vec![read_plan(py, plan, "plan")?];
    if let Some(other) = compare {
        reports.push(read_plan(py, other, "compare")?);
    }
    let unit = if percent {
        BatteryUnit::Percent
    } else {
        BatteryUnit::Mah
    };
    let instance = on.problem();
    py.detach(|| {
        let refs: Vec<&RequestReport> = reports.iter().collect();
        plans_svg(&instance.network, &instance.profile, &refs, unit)
    })
    .map_err(|e| to_py_err(py, e))
}

/// The figure of a plan as SVG text, the bytes ``swarmplan plot --plan P -o F`` writes: the
/// route on the network, every drone's battery against time with the in-flight transfers, and
/// the pad schedule of every stop. With ``compare``, a second plan of the same request beside
/// it on the same axes, the title giving both delivery times and the gap against it.
///
/// The plan is drawn on the instance it was made on (``Instance.plot`` draws plans given as
/// dicts or JSON text on an instance of one's choice). A ``Plan`` shows as this figure in
/// Jupyter (``Plan._repr_svg_``).
///
/// Parameters
/// ----------
/// plan : Plan
///     A plan as ``Instance.plan`` returns it.
/// compare : Plan, dict, str or None, default None
///     A second plan of the same request (its ``to_dict()`` or JSON text too), drawn as the
///     reference of the gap in the title (``--compare``).
/// percent : bool, default False
///     Batteries in percent of each drone's capacity instead of mAh (``--percent``).
///
/// Returns
/// -------
/// str
///     The SVG document; ``open("plan.svg", "w").write(svg)`` writes the command line's file.
///
/// Raises
/// ------
/// SwarmplanError
///     E8001 for a ``compare`` plan of another request; E6004, E6005 for a ``compare`` plan
///     made on another network, with another profile; E6001-E6003 for a ``compare`` that is no
///     plan document; E8003 for a plan that does not fit the instance.
#[pyfunction]
#[pyo3(signature = (plan, compare = None, percent = false))]
pub(crate) fn plot(
    py: Python<'_>,
    plan: &Bound<'_, Plan>,
    compare: Option<&Bound<'_, PyAny>>,
    percent: bool,
) -> PyResult<String> {
    svg_on(py, plan.get().made_by(), plan.as_any(), compare, percent)
}
