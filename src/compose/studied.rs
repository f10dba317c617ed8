//! One hop of a request's plan taken out as a hop file: the problem `swarmplan eaas` studies and
//! the Python package's `Instance.hop` returns.

use super::{Context, PlanOptions, RequestReport, RouteMethod};
use crate::eaas::exact::EndPads;
use crate::eaas::exact::Objective;
use crate::eaas::hop_file::{HopFile, HopPlan, HOP_FILE_SCHEMA_VERSION};
use crate::error::{Error, Result};
use crate::problem::Request;

impl Context {
    /// Plans `request` with `options` and returns hop `index` of the plan as a hop file: its
    /// path, its departure batteries as planned, and the pads at its end (none into the
    /// destination), recorded as made with the profile called `profile_name`.
    ///
    /// # Errors
    /// E4110 (field `hop`) when the plan has no hop `index`; those of [`Context::plan`] and
    /// [`super::Planner::studied_hop`].
    pub fn hop_file(
        &self,
        request: &Request,
        options: &PlanOptions,
        index: usize,
        profile_name: &str,
    ) -> Result<HopFile> {
        let report = self.plan(request, options)?;
        self.hop_file_of(&report, index, profile_name)
    }

    /// Hop `index` of a planned request's report as a hop file (see [`Context::hop_file`]).
    ///
    /// # Errors
    /// E4110 (field `hop`) when the plan has no hop `index`; those of
    /// [`super::Planner::studied_hop`].
    pub fn hop_file_of(
        &self,
        report: &RequestReport,
        index: usize,
        profile_name: &str,
    ) -> Result<HopFile> {
        let hops = &report.plan.hops;
        let hop = hops.get(index).ok_or_else(|| {
            Error::invalid(
                "E4110",
                "hop",
                format!("hop {index} of a plan with {} hop(s)", hops.len()),
                "give a hop index below the number of hops of the request's plan",
            )
        })?;
        let planner = self.planner(&report.swarm, report.options.sharing);
        let (problem, objective) = planner.studied_hop(hop)?;
        let end = match objective {
            Objective::NodeTime(EndPads {
                pads,
                pad_rate_mah_per_min,
            }) => Some(EndPads {
                pads,
                pad_rate_mah_per_min,
            }),
            Objective::MaxMinArrival | Objective::Feasible => None,
        };
        Ok(HopFile {
            schema_version: HOP_FILE_SCHEMA_VERSION,
            request_id: report.request.id.clone(),
            hop_index: index,
            from: hop.path.first().cloned().unwrap_or_default(),
            to: hop.path.last().cloned().unwrap_or_default(),
            path: hop.path.clone(),
            profile: Some(profile_name.to_string()),
            end,
            made_on: Some(self.fingerprint().clone()),
            plan: Some(HopPlan::from(&report.options)),
            hop: problem,
        })
    }
}

impl From<&PlanOptions> for HopPlan {
    fn from(o: &PlanOptions) -> HopPlan {
        HopPlan {
            sharing: o.sharing,
            positioning: o.positioning,
            route: o.route.to_string(),
            support: o.support,
        }
    }
}

impl TryFrom<&HopPlan> for PlanOptions {
    type Error = String;

    /// The combination a hop file records; the error names a route this version does not have.
    fn try_from(p: &HopPlan) -> std::result::Result<PlanOptions, String> {
        let route: RouteMethod = serde_json::from_value(serde_json::Value::from(p.route.as_str()))
            .map_err(|_| format!("`{}` is not a route method", p.route))?;
        Ok(PlanOptions {
            sharing: p.sharing,
            positioning: p.positioning,
            route,
            support: p.support,
        })
    }
}
