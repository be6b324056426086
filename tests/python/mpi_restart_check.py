"""Restart of a distributed run, bit for bit (docs/parallel.md, docs/restart.md; ctest label "mpi").

Runs DECK under `mpirun -np N` with --dump-every (the uninterrupted run, which writes its dumps
on the way), then restarts from one of its dumps under `mpirun -np N` into a NEW directory, and
requires every result file of the uninterrupted run to come out byte-identical from the restart:
the CSV histories (cut at the dump and continued), the VTU frames and the d3plot family written
after the dump, and the later restart dumps themselves. Only run.json and d3hsp.txt (wall times,
command lines) and the dumps up to the one restarted from (the restart does not rewrite them)
are not compared. Files the restart writes that the uninterrupted run did not: an error.

With --interrupt-after F a further run on N ranks (of the deck --interrupt-deck-command writes,
or DECK) is sent SIGTERM (to one rank only; the ranks
agree on an interrupt) F times the first run's wall time after
its first frame, must end with
the interrupt's restart dump, and its restart must give the files of an uninterrupted run without
dumps.

With --other-ranks M,...: the same dump restarted on M ranks (1: without mpirun) must warn that
the rank count differs, and its CSV histories must equal the uninterrupted run's to round-off
(--rtol of the column's scale, as mpi_ranks_check.py compares ranks with one process).

Standard library only. Exit status 0 and "OK" on success; prints what differed otherwise.
"""
import argparse
import filecmp
import os
import shutil
import signal
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from mpi_ranks_check import compare_csv  # noqa: E402

NOT_COMPARED = {"run.json", "d3hsp.txt"}


def run(cmd):
    p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if p.returncode != 0:
        print("FAILED (%d): %s\n%s" % (p.returncode, " ".join(cmd), p.stdout))
        sys.exit(1)
    return p.stdout


def dumps_in(directory):
    return sorted(f for f in os.listdir(directory) if f.startswith("d3dump_") and f.endswith(".h5"))


def compare(full, restarted, restarted_from):
    """Every file of `full` (less NOT_COMPARED and the dumps up to `restarted_from`) equal in
    `restarted`; returns the number of files compared."""
    problems, compared = [], 0
    skip = set(NOT_COMPARED)
    skip.update(d for d in dumps_in(full) if d <= restarted_from)
    full_files = sorted(f for f in os.listdir(full) if f not in skip)
    for name in full_files:
        a, b = os.path.join(full, name), os.path.join(restarted, name)
        if not os.path.exists(b):
            problems.append("%s: missing after the restart" % name)
        elif not filecmp.cmp(a, b, shallow=False):
            problems.append("%s: differs from the uninterrupted run's" % name)
        else:
            compared += 1
    extra = sorted(set(os.listdir(restarted)) - set(os.listdir(full)) - skip)
    for name in extra:
        problems.append("%s: written by the restart only" % name)
    if problems:
        print("FAILED: restart from %s\n  %s" % (restarted_from, "\n  ".join(problems)))
        sys.exit(1)
    return compared


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("--rigidflex", required=True)
    ap.add_argument("--mpirun", required=True)
    ap.add_argument("--deck", required=True)
    ap.add_argument("--work", required=True)
    ap.add_argument("--ranks", type=int, default=2)
    ap.add_argument("--dump-every", required=True)
    ap.add_argument("--restart-from", default="d3dump_0002.h5")
    ap.add_argument("--interrupt-after", type=float, default=0.0)
    ap.add_argument("--interrupt-deck-command", default="",
                    help="a generator whose output is the deck of the interrupt test (default: "
                         "--deck); it should run for a second or more")
    ap.add_argument("--other-ranks", default="")
    ap.add_argument("--rtol", type=float, default=1e-10)
    args = ap.parse_args()

    mpirun = [args.mpirun, "--oversubscribe", "--allow-run-as-root", "--bind-to", "none", "-np",
              str(args.ranks), args.rigidflex]
    shutil.rmtree(args.work, ignore_errors=True)
    os.makedirs(args.work)
    full = os.path.join(args.work, "full")
    start = time.monotonic()
    out = run(mpirun + ["run", args.deck, "-o", full, "--dump-every", args.dump_every])
    span = time.monotonic() - start
    dumps = dumps_in(full)
    if args.restart_from not in dumps:
        print("FAILED: the run on %d ranks wrote %s, not %s\n%s" %
              (args.ranks, dumps, args.restart_from, out))
        sys.exit(1)
    restarted = os.path.join(args.work, "restarted")
    run(mpirun + ["restart", os.path.join(full, args.restart_from), "-o", restarted, "--quiet"])
    n = compare(full, restarted, args.restart_from)
    print("restart from %s on %d ranks: %d files identical (%s dumps written)" %
          (args.restart_from, args.ranks, n, len(dumps)))

    for m in [int(x) for x in args.other_ranks.split(",") if x]:
        other = os.path.join(args.work, "restarted_on_%d" % m)
        launch = [args.rigidflex] if m == 1 else (
            [args.mpirun, "--oversubscribe", "--allow-run-as-root", "--bind-to", "none", "-np",
             str(m), args.rigidflex])
        text = run(launch + ["restart", os.path.join(full, args.restart_from), "-o", other])
        expected = "the dumped run used %d MPI rank(s), this restart uses %d" % (args.ranks, m)
        if expected not in text:
            print("FAILED: no warning '%s' from the restart on %d ranks:\n%s" % (expected, m, text))
            sys.exit(1)
        worst = []
        for name in sorted(f for f in os.listdir(full) if f.endswith(".csv")):
            d, _ = compare_csv(name, os.path.join(full, name), os.path.join(other, name),
                               args.rtol, 0.0)
            worst.append("%s %.2g" % (name, d))
        print("restart from %s on %d ranks (dumped on %d): %s" %
              (args.restart_from, m, args.ranks, ", ".join(worst)))

    if args.interrupt_after > 0.0:
        # The deck of the interrupt test and its uninterrupted run without dumps (the reference
        # for the files after the interrupt, and the wall time the delay is a fraction of).
        deck = args.deck
        if args.interrupt_deck_command:
            deck = os.path.join(args.work, "interrupt_deck.k")
            with open(deck, "w") as f:
                subprocess.run(args.interrupt_deck_command.split(), stdout=f, check=True)
        plain = os.path.join(args.work, "plain")
        start = time.monotonic()
        run(mpirun + ["run", deck, "-o", plain, "--quiet"])
        span = time.monotonic() - start
        # The interrupted run: SIGTERM to the rigidflex process of one rank (not to mpirun, which
        # would end the job at once); every rank ends in the same cycle and rank 0 writes the
        # dump. The delay after the first frame is a fraction of the uninterrupted run's wall time
        # (start-up included); a run that ended before the signal is tried again with half the
        # delay.
        delay, stopped, dumps = args.interrupt_after * span, None, []
        for attempt in range(4):
            stopped = os.path.join(args.work, "interrupted%d" % attempt)
            p = subprocess.Popen(mpirun + ["run", deck, "-o", stopped, "--quiet"],
                                 stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
            # The signal handlers are installed before the model is read; the first frame (at
            # t = 0, in the first cycle) shows the time loop has started. A signal during MPI's
            # start-up would end the process instead.
            waited = 0.0
            while p.poll() is None and waited < 120.0 and not any(
                    f.startswith(("frames_", "d3plot")) for f in
                    (os.listdir(stopped) if os.path.isdir(stopped) else [])):
                time.sleep(0.01)
                waited += 0.01
            time.sleep(delay)
            ranks = subprocess.run(["pgrep", "-P", str(p.pid)], stdout=subprocess.PIPE, text=True)
            children = [int(x) for x in ranks.stdout.split()]
            if children:
                os.kill(children[-1], signal.SIGTERM)
            text, _ = p.communicate(timeout=600)
            dumps = dumps_in(stopped) if os.path.isdir(stopped) else []
            if p.returncode == 0 and not dumps:
                print("interrupt after %.2f s came after the end; again" % delay)
                delay *= 0.5
                continue
            if len(dumps) != 1:
                print("FAILED: the interrupted run (exit %d) left dumps %s\n%s" %
                      (p.returncode, dumps, text))
                sys.exit(1)
            break
        if len(dumps) != 1:
            print("FAILED: no run was interrupted before its end")
            sys.exit(1)
        again = os.path.join(args.work, "after_interrupt")
        run(mpirun + ["restart", os.path.join(stopped, dumps[0]), "-o", again, "--quiet"])
        n = compare(plain, again, dumps[0])
        print("interrupted on %d ranks (exit %d) after %.2f s, restart from its dump: %d files "
              "identical" % (args.ranks, p.returncode, delay, n))
    print("OK")


if __name__ == "__main__":
    main()
