//! The Python package's tests, run by `cargo test` so that the README's one test command covers
//! both fronts: a virtual environment inside the clone (`target/python/venv`) with the pinned
//! tools of `python/requirements-test.txt`, the package built from this checkout with maturin
//! (`pip install .`, its own cargo target directory), then pytest on `python/tests`, which
//! compares the package with the `swarmplan` binary this run built.
//!
//! Needs Python 3.9 or newer with `venv` and pip's access to PyPI. Set `SWARMPLAN_SKIP_PYTHON=1`
//! to leave it out on a machine without them (the test then says so and passes).

use std::path::{Path, PathBuf};
use std::process::Command;

fn run(what: &str, command: &mut Command) {
    let out = command
        .output()
        .unwrap_or_else(|e| panic!("{what}: cannot start: {e}"));
    assert!(
        out.status.success(),
        "{what} failed ({}):\n{}\n{}",
        out.status,
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
}

/// `PATH` with `dir` first (the virtual environment's `maturin`).
fn path_with(dir: &Path) -> std::ffi::OsString {
    let mut paths = vec![dir.to_path_buf()];
    paths.extend(std::env::split_paths(
        &std::env::var_os("PATH").unwrap_or_default(),
    ));
    std::env::join_paths(paths).expect("paths without separators")
}

#[test]
fn the_python_package_passes_its_tests() {
    if std::env::var_os("SWARMPLAN_SKIP_PYTHON").is_some() {
        eprintln!("SWARMPLAN_SKIP_PYTHON is set: the Python package's tests are left out");
        return;
    }
    let repo = Path::new(env!("CARGO_MANIFEST_DIR"));
    let base: PathBuf = repo.join("target").join("python");
    let venv = base.join("venv");
    let python = std::env::var("PYTHON").unwrap_or_else(|_| "python3".into());
    if !venv.join("bin").join("python").exists() {
        run(
            "python3 -m venv (install Python 3.9+ with venv: Debian's python3-venv)",
            Command::new(&python).args(["-m", "venv"]).arg(&venv),
        );
    }
    let py = venv.join("bin").join("python");
    run(
        "pip install -r python/requirements-test.txt",
        Command::new(&py)
            .args([
                "-m",
                "pip",
                "install",
                "-q",
                "--disable-pip-version-check",
                "-r",
            ])
            .arg(repo.join("python").join("requirements-test.txt")),
    );
    run(
        "pip install . (maturin build of the package)",
        Command::new(&py)
            .args([
                "-m",
                "pip",
                "install",
                "-q",
                "--disable-pip-version-check",
                "--no-build-isolation",
                "--force-reinstall",
                "--no-deps",
            ])
            .arg(repo)
            .env("CARGO_TARGET_DIR", base.join("cargo"))
            .env("PATH", path_with(&venv.join("bin"))),
    );
    run(
        "pytest python/tests",
        Command::new(&py)
            .args(["-m", "pytest", "-q", "-p", "no:cacheprovider"])
            .arg(repo.join("python").join("tests"))
            .current_dir(repo)
            .env("SWARMPLAN_BIN", env!("CARGO_BIN_EXE_swarmplan")),
    );
}
