//! The `swarmplan` command line. Thin: parsing and dispatch live in [`swarmplan::cli`].

fn main() {
    std::process::exit(swarmplan::cli::main());
}
