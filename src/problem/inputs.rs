//! The instance files a front end names (a network, a profile, a request set), each one not
//! given replaced by a shipped one ([`shipped`]), read and validated together so that a file
//! that cannot be read or parsed does not hide a problem of another.

use super::{io, shipped, Instance, Network, Profile, RequestSet};
use crate::error::{both, Error, Result};
use shipped::{Shipped, PAPER_195};
use std::path::{Path, PathBuf};

/// A network and a profile as given: files, or the shipped ones.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct InstanceFiles {
    /// Skyway network (JSON); `None`: the shipped one.
    pub network: Option<PathBuf>,
    /// Parameter profile (TOML); `None`: the shipped one.
    pub profile: Option<PathBuf>,
    /// Read the paper word for word where it can be read several ways (the profile's
    /// `[readings]` become [`crate::problem::profile::Readings::literal`]).
    pub literal: bool,
}

impl InstanceFiles {
    /// Reads and validates the network and the profile (the shipped paper-195 ones when not
    /// given), reporting every violation of both.
    ///
    /// # Errors
    /// The read, parse and validation errors of both files.
    pub fn load(&self) -> Result<Instance> {
        self.load_or(&PAPER_195)
    }

    /// [`InstanceFiles::load`] with `shipped` for the files not given.
    ///
    /// # Errors
    /// The read, parse and validation errors of both files.
    pub fn load_or(&self, shipped: &Shipped) -> Result<Instance> {
        let network: Result<Network> = match &self.network {
            Some(p) => io::read_json(p),
            None => io::parse_json(shipped.network, shipped.network_name),
        };
        let (network, profile) = both(network, self.read_profile(shipped))?;
        Instance::new(network, profile)
    }

    /// [`InstanceFiles::load`] and [`load_requests`] together, reporting the violations of the
    /// network, the profile and the request set at once.
    ///
    /// # Errors
    /// Those of the three files.
    pub fn load_with_requests(&self, requests: Option<&Path>) -> Result<(Instance, RequestSet)> {
        both(self.load(), load_requests(requests))
    }

    /// Reads and validates the profile alone, for a front end that needs no network.
    ///
    /// # Errors
    /// The read, parse and validation errors of the profile.
    pub fn load_profile(&self) -> Result<Profile> {
        let profile = self.read_profile(&PAPER_195)?;
        let violations = super::validate::validate_profile(&profile);
        if violations.is_empty() {
            Ok(profile)
        } else {
            Err(Error::Invalid(violations))
        }
    }

    /// The profile given (or `shipped`'s), the literal readings applied, not validated.
    fn read_profile(&self, shipped: &Shipped) -> Result<Profile> {
        let mut profile: Profile = match &self.profile {
            Some(p) => io::read_toml(p)?,
            None => io::parse_toml(shipped.profile, shipped.profile_name)?,
        };
        if self.literal {
            profile.readings = super::profile::Readings::literal();
        }
        Ok(profile)
    }
}

/// Reads a request set (the file given, or the shipped paper-195 requests) and checks its
/// header and ids (E3001, E3002, E3102); the requests themselves are checked by the caller
/// against the network.
///
/// # Errors
/// The read and parse errors of the file, E3001, E3002, E3102.
pub fn load_requests(path: Option<&Path>) -> Result<RequestSet> {
    match path {
        Some(p) => shipped::checked_set(io::read_json(p)?),
        None => shipped::requests(),
    }
}
