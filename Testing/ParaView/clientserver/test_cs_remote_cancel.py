"""Client/server integration test (issue 19 item 1, issue 16 item 6): a VesselCenterline run on a
2-rank pvserver cancelled from the client (vesseltouch.remote_cancel).

Run as ``pvpython test_cs_remote_cancel.py [--size N] [--ranks R]`` with VESSELTOUCH_PLUGIN set,
on a display (vtouch-xvfb-run). A raw-angiogram VesselPhantom (N^3, 128 by default) is written
built in as a float NRRD, read in pieces on the server and extracted with a long run to cancel,
as the built-in Cancel test does (gui_background_extract.py): Automatic off, the range from the
tissue's level up (LowerThreshold LONG_RUN_LOWER), DownsampleFactor 1, so most of the tissue is
the vessel mask, coded at full resolution with DistributedExtraction on (minutes uncancelled):
- cancelled from a progress callback (the first progress event that names the cancel port and
  reports progress past the start): the update returns with an empty output and ExtractionMessage
  "Cancelled." (the message the built-in Cancel gives), the server acknowledged the token;
- cancelled from another Python thread (waiting on an event the progress observer sets), the
  same;
- a wrong token is refused ("wrong token") and the run goes on: the right token at the next
  progress event cancels it;
- cancelled in the first rank's stitch (h18q: the long silent stretch of this run, 74 of its
  85 s at 128^3 before the stitch had check points): the server's progress keeps coming during
  the stitch (at least --stitch-reports reports whose text names it, past the pieces' share,
  50 %), a cancel at the
  last of them stops the run ("Cancelled.", every rank: the next step works), and no gap between
  two progress reports the client saw (or the update's start and end) is longer than
  MAX_GAP_SHARE of the run (counted on the client's reports, the bound relative to the run);
- then a second extraction (the scaling benchmark's tree, 64^3, thresholded) succeeds on the
  same server (paths, no message): no rank was left waiting in an exchange; and the server exits
  when the client disconnects (run_connected).
Every wait has a time-out: a watchdog kills the server if an update does not return. Prints the
time from the cancel's send to the update's return (not asserted). Exits non-zero on failure.
"""

import argparse
import os
import shutil
import socket
import sys
import tempfile
import threading
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(os.path.dirname(HERE)))
sys.path[:0] = [HERE, os.path.dirname(HERE), os.path.join(ROOT, "Utilities", "bench")]
from vtouch_pvserver import run_connected  # noqa: E402
from vtouch_testing import Check, plugin_path  # noqa: E402
from scaling_bench import write_tree_nrrd  # noqa: E402
from vtouch_pvserver import write_float_nrrd  # noqa: E402

from paraview import servermanager as sm  # noqa: E402
from paraview import simple  # noqa: E402

PLUGIN = plugin_path()
CHECK = Check("client/server remote cancel")
check = CHECK.true
# An update that has not returned by then is a hang (a cancelled run returns in about a second;
# the uncancelled small run in seconds).
WATCHDOG_S = 240.0
# The longest stretch without a progress report the client may see, as a share of the run (start
# and end of the update included). Project rule (h18q): with the stitch's check points the longest
# was 1.9-2.3 s of 13-30 s (the coder's tracing); before them, 75 s of 85 s (the stitch).
MAX_GAP_SHARE = 0.4
# The phantom's tissue is about 400 +- 15 (its 25th percentile 390): from 380 up most of it is
# "vessel", a mask the coder takes minutes on at full resolution.
LONG_RUN_LOWER = 380.0


def message_of(data):
    a = data.GetFieldData().GetAbstractArray("ExtractionMessage")
    return a.GetValue(0) if a is not None and a.GetNumberOfValues() else ""


def write_phantom(path, size):
    simple.LoadPlugin(PLUGIN, remote=False, ns=globals())
    phantom = VesselPhantom(Shape="Raw angiogram", Dimensions=[size] * 3, Seed=2)  # noqa: F821
    write_float_nrrd(path, sm.Fetch(phantom))
    simple.Delete(phantom)


def extract(volume, canceller_factory, label, **settings):
    """One update of a fresh VesselCenterline on `volume` with a RemoteCancel from
    `canceller_factory(centerline)`; returns (output, canceller, seconds from the send)."""
    centerline = simple.VesselCenterline(Input=volume, DistributedExtraction=1, **settings)
    canceller = canceller_factory(centerline)
    start = time.monotonic()
    centerline.UpdatePipeline()
    end = time.monotonic()
    canceller.close()
    data = sm.Fetch(centerline)
    after_send = end - canceller.sent_at if canceller.sent_at is not None else None
    print("%s: run %.2f s, port %s, answer %r at progress %.2f, message %r, %d lines, "
          "cancel to return %s s"
          % (label, end - start, canceller.port, canceller.answer, canceller.progress,
             message_of(data),
             data.GetNumberOfLines(),
             "%.3f" % after_send if after_send is not None else "-"))
    simple.Delete(centerline)
    return data, canceller, after_send


LONG = dict(AutomaticIntensityRange=0, LowerThreshold=LONG_RUN_LOWER, DownsampleFactor=1)


def check_stitch_cancel(volume, stitch_reports):
    """A run cancelled at the `stitch_reports`-th progress report of the first rank's stitch."""
    from vesseltouch.remote_cancel import RemoteCancel
    seen = []

    def in_stitch(centerline):
        def on_progress(fraction, text):
            seen.append((time.monotonic(), fraction, text.endswith("(stitching)")))
            return sum(1 for _, f, stitching in seen if stitching and f > 0.5) >= stitch_reports
        return RemoteCancel(centerline, on_progress=on_progress)
    started = time.monotonic()
    data, c, _ = extract(volume, in_stitch, "cancel in the first rank's stitch", **LONG)
    ended = time.monotonic()
    stitch_seen = [f for _, f, stitching in seen if stitching and f > 0.5]
    check(len(stitch_seen) >= stitch_reports,
          "the client saw the stitch's progress (%d reports of the stitch, past 50 %%: %s)"
          % (len(stitch_seen), stitch_seen))
    check(c.cancelled() and message_of(data) == "Cancelled." and data.GetNumberOfLines() == 0,
          "a cancel in the stitch stops the run (%r, %r, %d lines)"
          % (c.answer, message_of(data), data.GetNumberOfLines()))
    moments = [started] + [t for t, _, _ in seen] + [ended]
    gaps = [b - a for a, b in zip(moments, moments[1:])]
    longest = max(gaps)
    print("stitch cancel: %d reports in %.2f s, the longest gap %.2f s (%.0f %% of the run)"
          % (len(seen), ended - started, longest, 100.0 * longest / (ended - started)))
    check(longest <= MAX_GAP_SHARE * (ended - started),
          "no stretch without a progress report longer than %.0f %% of the run (the longest "
          "%.2f s of %.2f s, %d reports)"
          % (100.0 * MAX_GAP_SHARE, longest, ended - started, len(seen)))


def body(folder, size, cancel_at, cancel_after_s, stitch_reports):
    from vesseltouch.remote_cancel import RemoteCancel
    volume = simple.OpenDataFile(os.path.join(folder, "angio%d.nrrd" % size))
    volume.UpdatePipeline()

    # 1. From a progress callback, once the port is known and the run is under way.
    def from_callback(centerline):
        return RemoteCancel(centerline, on_progress=lambda fraction, text: fraction > cancel_at)
    data, c, _ = extract(volume, from_callback, "cancel from a progress callback", **LONG)
    check(c.port is not None, "the progress text named the cancel port")
    check(c.cancelled(), "the server acknowledged the cancel (answer %r, error %r)"
          % (c.answer, c.error))
    check(message_of(data) == "Cancelled.", "the message is 'Cancelled.' (%r)" % message_of(data))
    check(data.GetNumberOfLines() == 0 and data.GetNumberOfPoints() == 0, "the output is empty")

    # 2. From another thread, which waits for the port (the observer's event).
    def from_thread(centerline):
        port_seen = threading.Event()
        canceller = RemoteCancel(
            centerline, on_progress=lambda fraction, text: port_seen.set() or False)

        def cancel_when_running():
            if port_seen.wait(WATCHDOG_S):
                time.sleep(cancel_after_s)  # a measurement's delay (0 in the ctest)
                canceller.cancel()
        threading.Thread(target=cancel_when_running, daemon=True).start()
        return canceller
    data, c, _ = extract(volume, from_thread, "cancel from another thread", **LONG)
    check(c.cancelled(), "the server acknowledged the thread's cancel (answer %r, error %r)"
          % (c.answer, c.error))
    check(message_of(data) == "Cancelled.", "the message is 'Cancelled.' (%r)" % message_of(data))
    check(data.GetNumberOfLines() == 0, "the output is empty")

    # 3. A wrong token is refused and changes nothing; the right one then cancels.
    wrong = {}

    def wrong_then_right(centerline):
        holder = []

        def on_progress(fraction, text):
            c = holder[0]
            if c.port is None:
                return False
            if "answer" not in wrong:
                with socket.create_connection((c.host, c.port), 5.0) as s:
                    s.settimeout(5.0)
                    s.sendall(b"not-the-token\n")
                    wrong["answer"] = s.makefile().readline().strip()
                return False
            return True  # the next progress event: the run went on; now the right token
        holder.append(RemoteCancel(centerline, on_progress=on_progress))
        return holder[0]
    data, c, _ = extract(volume, wrong_then_right, "a wrong token, then the right one", **LONG)
    check(wrong.get("answer") == "wrong token", "a wrong token is refused (%r)" % wrong)
    check(c.cancelled() and message_of(data) == "Cancelled.",
          "the run went on after the wrong token and the right one cancelled it (%r, %r)"
          % (c.answer, message_of(data)))

    # 4. In the first rank's stitch: the progress past the pieces' share (50 %) is the stitch's.
    if stitch_reports > 0:
        check_stitch_cancel(volume, stitch_reports)

    # 5. The server still answers: a small tree extracts (paths, no message).
    small = os.path.join(folder, "tree64.nrrd")
    write_tree_nrrd(small, (64, 64, 64))
    volume_small = simple.OpenDataFile(small)
    data, c, _ = extract(volume_small, RemoteCancel, "no cancel, small tree",
                         AutomaticIntensityRange=0, LowerThreshold=550)
    check(data.GetNumberOfLines() > 0 and message_of(data) == "",
          "the next extraction on the same server succeeds (%d lines, %r)"
          % (data.GetNumberOfLines(), message_of(data)))
    simple.Delete(volume_small)
    simple.Delete(volume)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--size", type=int, default=128)
    parser.add_argument("--ranks", type=int, default=2)
    # The callback's cancel: at the first progress event past this fraction (0: as soon as the
    # run reports any; 0.3: in the coder's local coding, Docs/CLIENT-SERVER.md's measurements).
    parser.add_argument("--cancel-at", type=float, default=0.0)
    # The thread's cancel: this long after the port is known (measurements of a cancel in the
    # coder's local stages; 0 in the ctest).
    parser.add_argument("--cancel-after-s", type=float, default=0.0)
    parser.add_argument("--watchdog-s", type=float, default=WATCHDOG_S)
    # The stitch's cancel: at this many progress reports of the first rank's stitch (0: no such
    # case; at 256^3 the pieces take minutes before the stitch). One: since the stitch's grids
    # (h18s) the stitch of this run takes 1.5-3 s and ParaView forwards a report at most once a
    # second, so a later report may come after the stitch has ended (3 until then).
    parser.add_argument("--stitch-reports", type=int, default=1)
    args = parser.parse_args()
    folder = tempfile.mkdtemp(prefix="vtouch-cs-cancel-")
    write_phantom(os.path.join(folder, "angio%d.nrrd" % args.size), args.size)

    def run(server):
        watchdog = threading.Timer(args.watchdog_s, server.kill)
        watchdog.start()
        try:
            body(folder, args.size, args.cancel_at, args.cancel_after_s, args.stitch_reports)
        finally:
            watchdog.cancel()
    try:
        run_connected(PLUGIN, check, run, ranks=args.ranks, pass_server=True)
    finally:
        shutil.rmtree(folder, ignore_errors=True)
    sys.exit(CHECK.finish())


if __name__ == "__main__":
    main()
