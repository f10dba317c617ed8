//! The `swarmplan` command line. Thin: parsing and dispatch live in [`swarmplan::cli`].

/// The allocator of the command line (the library leaves the choice to its users).
#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

fn main() {
    std::process::exit(swarmplan::cli::main());
}
