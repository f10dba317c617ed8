"""A sharing policy written in Python, scored against the proven optimum on 100 hops.

The policy, "late top-up": every support drone gives what it can spare above its reserve to the
delivery drone it can reach that arrives lowest, at the end of the hop (so no consumer is topped
up above its capacity early on). Each hop is the first hop of a request of paper-195, as
`swarmplan eaas` takes it; the policy's node time (at a stop) or lowest arrival battery (into a
destination) is compared with the optimum over every continuous-time schedule.

    python python/examples/policy_gaps.py [--hops 100] [--figure policy_gaps.png]

Prints one line per hop and a summary; saves a histogram of the gaps when matplotlib is
installed. About 10 s on 2 cores.
"""

import argparse
import statistics

import numpy as np

import swarmplan


def late_top_up(hop):
    """One transfer per support drone, at the end of the hop, to the lowest reachable consumer."""
    roles = hop.roles
    slot = hop.initial_slot
    tt = hop.tt_min
    # Each drone's battery at the hop's end without sharing.
    rates = hop.rates_mah_per_min[:, np.arange(hop.drones), slot]
    arrival = hop.battery_mah - hop.durations_min @ rates
    busy, schedule = set(), []
    for s in (d for d in range(hop.drones) if roles[d] == "support"):
        spare = arrival[s] - hop.delta_mah
        moves = [m for m in hop.moves("paper") if m["support"] == s
                 and m["consumer"] not in busy and m["partner"] not in busy]
        if spare <= 0 or not moves:
            continue
        m = min(moves, key=lambda m: arrival[m["consumer"]])
        need = hop.capacity_mah[m["consumer"]] - arrival[m["consumer"]]
        minutes = min(spare, need) / hop.rho_mah_per_min
        minutes = min(minutes, 0.999 * tt)  # keep within [0, tt] whatever the numbers
        if minutes <= 0:
            continue
        busy.update(x for x in (m["consumer"], m["partner"]) if x is not None)
        schedule.append(dict(support=s, consumer=m["consumer"], consumer_slot=m["consumer_slot"],
                             start_min=tt - minutes, end_min=tt))
    return schedule


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--hops", type=int, default=100)
    parser.add_argument("--figure", default="policy_gaps.png")
    args = parser.parse_args()
    instance = swarmplan.Instance.embedded("paper-195")
    gaps, labels = [], {}
    for request_id in instance.request_ids[: args.hops]:
        hop = instance.hop(request_id, 0)
        result = swarmplan.evaluate(hop, late_top_up(hop))
        gap = result.gap
        if gap is not None and gap["relative"] is not None:
            # A gap is a loss: positive is worse under either objective.
            worse = gap["relative"]
            gaps.append(100.0 * worse)
            shown = f"{100.0 * worse:8.3f}% against the {gap['reference']}"
        else:
            labels[result.gap_label] = labels.get(result.gap_label, 0) + 1
            shown = result.gap_label
        print(f"{request_id} hop 0 {len(hop.path) - 1:2d} edge(s) {hop.drones:2d} drones: "
              f"feasible {result.feasible!s:5} value {result.value!s:>20} {shown}")
    print(f"{len(gaps)} hops with a gap: mean {statistics.mean(gaps):.3f}%, "
          f"median {statistics.median(gaps):.3f}%, max {max(gaps):.3f}%; without: {labels or 'none'}")
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("matplotlib is not installed: no figure (pip install matplotlib)")
        return
    fig, ax = plt.subplots(figsize=(6, 3.5))
    ax.hist(gaps, bins=30, color="#1f77b4")
    ax.set_xlabel("gap to the continuous-time optimum, % (worse is positive)")
    ax.set_ylabel("hops")
    ax.set_title(f"late top-up on {len(gaps)} first hops of paper-195")
    fig.tight_layout()
    fig.savefig(args.figure, dpi=120)
    print(f"wrote {args.figure}")


if __name__ == "__main__":
    main()
