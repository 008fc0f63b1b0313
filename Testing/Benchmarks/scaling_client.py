"""Client/server scaling run (issue 19, item 4): one volume on an N-rank pvserver, measured from the
client. Run by Utilities/bench/scaling_bench.py (section "scaling" of Utilities/bench/run_bench.py)
under Testing/Utilities/vtouch-xvfb-run, or by hand:

    Testing/Utilities/vtouch-xvfb-run pvpython Testing/Benchmarks/scaling_client.py \
        --plugin build/lib/paraview-5.11/plugins/VesselTouch/VesselTouch.so \
        --volume vessels.nrrd --ranks 2 [--distributed] --lower 500 --upper 65535 --json out.json

Starts `mpiexec -np N pvserver` on 127.0.0.1 (Testing/ParaView/clientserver/vtouch_pvserver.py:
free port, every wait timed out, the process group ended), connects, loads the plugin on both
sides, and measures what the user waits for, in order:
  read_s            the reader's UpdatePipeline (each rank reads its piece);
  (--mip-first: the MIP shown now, as in the GUI, first_frame_s; else after the delivery)
  centerline_s      VesselCenterline's UpdatePipeline, the reader already updated (the filter may
                    ask for more than the reader's piece, ghost layers: that re-read is in here;
                    piece_reader_bytes_read.rank<r>: what each rank's reader read for it);
  stage_<name>_s    every "<Name>Seconds" array of the filter's field data: the filter's and the
                    coder's stage times on rank 0 (Coder<Stage>Seconds), and distributed: each
                    rank's own extraction (PieceExtractSeconds, the slowest rank and
                    stage_pieceExtract_s.rank<r>), the gather and the stitch on rank 0, and
                    where each rank's time goes (Docs/SCALING.md, "Where the distributed
                    filter's time goes"): stage_pieceUpstream_s (the filter's last request to
                    its RequestData: the reader re-executing for the grown piece),
                    stage_pieceReader_s and stage_pieceReaderValueRange_s (the reader's own
                    RequestData, 0 when it did not run), stage_pieceBeforeExtract_s,
                    stage_pieceMask_s, stage_pieceCode_s (of the extraction),
                    stage_pieceAfterExtract_s, stage_pieceGatherWait_s (waiting at the gather
                    for the last rank);
  centerline_before_request_s, centerline_request_to_exit_s, centerline_after_request_data_s
                    distributed: centerline_s cut by the ranks' epoch stamps (the earliest rank's
                    last request before its RequestData, the first rank leaving RequestData);
  deliver_s         binding the client's session: the skeleton appended on rank 0 and moved to the
                    client (vesseltouch/delivery.py);
  bytes_to_client   the delivered skeleton, marshalled as ParaView sends it
                    (vtkCommunicator::MarshalDataObject);
  peak_rss_mib.rank<r>, peak_rss_mib_max   each rank's VmHWM (/proc/<pid>/status) at the end,
                    baseline_rss_mib.rank<r> each rank's VmRSS once connected with the plugin loaded;
  client_peak_rss_mib;
  haptic.<phase>.<statistic>   the client's real-time loop (simulated device, the hand sweeping the
                    first path) for --seconds per phase: "idle" (nothing else) and "render" (the
                    server renders the MIP of the volume, remote rendering, the camera turning
                    every frame), each phase on a restarted session; frames_rendered.
Writes one flat JSON object; exits non-zero if a step failed (the error is in the JSON as "error").
"""

import argparse
import json
import os
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "ParaView", "clientserver"))
from vtouch_pvserver import ParallelServer, rank_processes, status_mib, wait_until  # noqa: E402

from paraview import servermanager as sm  # noqa: E402
from paraview import simple  # noqa: E402


def marshalled_bytes(data):
    from vtkmodules.vtkCommonCore import vtkCharArray
    from vtkmodules.vtkParallelCore import vtkCommunicator
    buffer = vtkCharArray()
    vtkCommunicator.MarshalDataObject(data, buffer)
    return int(buffer.GetNumberOfTuples() * buffer.GetNumberOfComponents())


def haptic_phase(session, seconds, render_view=None):
    """One phase on a restarted session: its loop statistics start at zero."""
    session.Stop()
    session.SetHandSweep(path=0, speed_mm_per_s=40.0)
    session.Start()
    frames = 0
    end = time.monotonic() + seconds
    while time.monotonic() < end:
        if render_view is None:
            time.sleep(0.05)
            continue
        camera = simple.GetActiveCamera()
        camera.Azimuth(3.0)
        simple.Render(render_view)
        frames += 1
    stats = session.GetStatistics()
    status = session.GetStatus()
    session.Stop()
    out = {k: float(v) for k, v in stats.items()}
    out["fault"] = int(status["fault"])
    return out, frames


def timeline(fd, start_epoch, end_epoch, result):
    """The distributed run's epoch stamps against the client's: the time before the request
    reached the ranks (the proxy's messages, the executive's information pass) and after the
    first rank left RequestData (the executive's end of the pass, ParaView's data information,
    the answer to the client)."""
    def values(name):
        a = fd.GetArray(name)
        return [] if a is None else [float(a.GetComponent(i, 0))
                                     for i in range(a.GetNumberOfTuples())]
    requests = [v for v in values("PieceRequestEpoch") if v > 0.0]
    exits = values("DistributedRequestDataExitEpoch")
    if requests:
        result["centerline_before_request_s"] = min(requests) - start_epoch
    if exits:
        result["centerline_after_request_data_s"] = end_epoch - exits[0]
    if requests and exits:
        result["centerline_request_to_exit_s"] = exits[0] - min(requests)


def show_mip(vesseltouch, reader, args, result):
    """A render view showing the volume as a MIP, rendered and composited on the server (the image
    sent to the client); the first frame's time in result["first_frame_s"]."""
    view = simple.CreateView("RenderView")
    view.ViewSize = [args.view_px, args.view_px]
    view.RemoteRenderThreshold = 0.0
    view.OrientationAxesVisibility = 0
    vesseltouch.ShowAsMIP(reader, view)
    view.ResetCamera()
    t = time.perf_counter()
    simple.Render(view)
    result["first_frame_s"] = time.perf_counter() - t
    return view


def measure(args, server, result):
    plugin = os.path.abspath(args.plugin)
    simple.LoadPlugin(plugin, remote=True)
    simple.LoadPlugin(plugin, remote=False)
    import vesseltouch  # the plugin's Python package: importable once the plugin is loaded
    result["ranks"] = sm.ActiveConnection.GetNumberOfDataPartitions()
    pids = wait_until(lambda: rank_processes(server), 10.0)
    result["rank_pids_found"] = len(pids)
    for rank, pid in pids.items():
        result["baseline_rss_mib.rank%d" % rank] = status_mib(pid, "VmRSS")

    reader = simple.OpenDataFile(args.volume)
    t = time.perf_counter()
    reader.UpdatePipeline()
    result["read_s"] = time.perf_counter() - t
    info = reader.GetDataInformation()
    result["voxels"] = info.GetNumberOfPoints()

    view = None
    if args.mip_first:
        # The GUI's order: the volume shown as a MIP (rendered on the server) before Extract; the
        # view's representation then holds each rank's piece, which the reader copies from when
        # the filter asks for the piece grown by its ghost margin (Docs/READERS.md).
        view = show_mip(vesseltouch, reader, args, result)

    centerline = simple.VesselCenterline(Input=reader, AutomaticIntensityRange=0,
                                         LowerThreshold=args.lower, UpperThreshold=args.upper,
                                         DistributedExtraction=1 if args.distributed else 0)
    t = time.perf_counter()
    start_epoch = time.time()  # the ranks' stamps are system_clock epochs: one machine's clock
    centerline.UpdatePipeline()
    end_epoch = time.time()
    result["centerline_s"] = time.perf_counter() - t

    session = vesseltouch.logic()
    t = time.perf_counter()
    session.Bind(centerline)
    result["deliver_s"] = time.perf_counter() - t
    delivered = session._delivery.client_copy()
    result["skeleton_points"] = delivered.GetNumberOfPoints()
    result["skeleton_paths"] = delivered.GetNumberOfLines()
    result["bytes_to_client"] = marshalled_bytes(delivered)
    fd = delivered.GetFieldData()
    for i in range(fd.GetNumberOfArrays()):
        name = fd.GetArrayName(i) or ""
        array = fd.GetArray(i)
        if name.endswith("Seconds") and array is not None and array.GetNumberOfTuples():
            stage = name[:-len("Seconds")]
            key = "stage_%s_s" % (stage[0].lower() + stage[1:])
            values = [float(array.GetComponent(t, 0)) for t in range(array.GetNumberOfTuples())]
            result[key] = max(values)  # per-rank arrays (PieceExtractSeconds): the slowest rank
            if len(values) > 1:
                for rank, value in enumerate(values):
                    result["%s.rank%d" % (key, rank)] = value
    read = fd.GetArray("PieceReaderVoxelBytesRead")
    for rank in range(read.GetNumberOfTuples() if read is not None else 0):
        result["piece_reader_bytes_read.rank%d" % rank] = float(read.GetComponent(rank, 0))
    timeline(fd, start_epoch, end_epoch, result)
    message = fd.GetAbstractArray("ExtractionMessage")
    if message is not None and message.GetNumberOfValues() and message.GetValue(0):
        result["extraction_message"] = message.GetValue(0)

    session.SetDevice("simulated")
    idle, _ = haptic_phase(session, args.seconds)
    if view is None:
        view = show_mip(vesseltouch, reader, args, result)
    render, frames = haptic_phase(session, args.seconds, view)
    result["frames_rendered"] = frames
    for phase, stats in (("idle", idle), ("render", render)):
        for key, value in stats.items():
            result["haptic.%s.%s" % (phase, key)] = value

    for rank, pid in pids.items():
        result["peak_rss_mib.rank%d" % rank] = status_mib(pid, "VmHWM")
    peaks = [result["peak_rss_mib.rank%d" % r] for r in pids]
    result["peak_rss_mib_max"] = max(peaks) if peaks else float("nan")
    result["client_peak_rss_mib"] = status_mib(os.getpid(), "VmHWM")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--plugin", required=True)
    parser.add_argument("--volume", required=True)
    parser.add_argument("--ranks", type=int, default=2)
    parser.add_argument("--lower", type=float, default=500.0)
    parser.add_argument("--upper", type=float, default=65535.0)
    parser.add_argument("--distributed", action="store_true",
                        help="VesselCenterline's DistributedExtraction on (each rank codes its "
                             "piece); off: the first rank codes the whole volume")
    parser.add_argument("--mip-first", action="store_true",
                        help="show the MIP before extracting (the GUI's order), not after")
    parser.add_argument("--seconds", type=float, default=3.0, help="per haptic phase")
    parser.add_argument("--view-px", type=int, default=400)
    parser.add_argument("--json", required=True)
    args = parser.parse_args()
    result = {"requested_ranks": args.ranks, "distributed": int(args.distributed)}
    server = ParallelServer(ranks=args.ranks, start_timeout_s=180.0)
    failed = False
    try:
        server.start()
        simple.Connect("127.0.0.1", server.port)
        measure(args, server, result)
        simple.Disconnect()
    except Exception as e:  # noqa: BLE001 - written into the result, the run reported failed
        result["error"] = "%s: %s" % (type(e).__name__, e)
        result["server_output"] = server.output()[-4000:]
        failed = True
    finally:
        server.stop()
    with open(args.json, "w") as f:
        json.dump(result, f, indent=1, sort_keys=True)
    print(json.dumps({k: v for k, v in result.items() if k != "server_output"}, sort_keys=True))
    sys.exit(1 if failed else 0)


main()
