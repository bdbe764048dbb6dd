"""A picture of the rod punching a plug out of the plate (input/punch_through.yaml, a
quarter model) with ParaView. Needs X: run it through
../shared/tools/paraview/run_pvpython.sh, which starts xvfb.

    run_pvpython.sh scripts/paraview/punch_picture.py RESULT.xmf --out PNG [--time T]

At the last time (or --time): the live elements only (status 1: the eroded ones are
gone), the quarter reflected across x = 0 into the half y >= 0, warped by the
displacement (x 1), coloured by the equivalent plastic strain, seen from the cut y = 0
a little from below, so that the plug, the rod and the hole's wall show in section.
Prints one JSON line; exit status 0 when the PNG was written.
"""
import argparse
import json
import os
import sys


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("xmf")
    p.add_argument("--out", required=True)
    p.add_argument("--time", type=float, default=None)
    p.add_argument("--range", type=float, nargs=2, default=[0.0, 0.3], metavar=("MIN", "MAX"),
                   help="colour range of the plastic strain")
    p.add_argument("--size", type=int, nargs=2, default=[1000, 800])
    args = p.parse_args()
    if not os.path.exists(args.xmf):
        print(json.dumps({"ok": False, "error": "file not found: %s" % args.xmf}))
        return 2
    import paraview.simple as ps

    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    import picture_common as pc

    reader, t = pc.read_at(ps, args.xmf, args.time)
    alive = ps.Threshold(Input=reader)
    alive.Scalars = ["CELLS", "status"]
    try:  # ParaView 5.10 and later
        alive.LowerThreshold, alive.UpperThreshold = 0.5, 1.5
    except AttributeError:
        alive.ThresholdRange = [0.5, 1.5]
    warp = ps.WarpByVector(Input=alive)
    warp.Vectors = ["POINTS", "displacement"]
    warp.ScaleFactor = 1.0
    half = ps.Reflect(Input=warp)
    half.Plane = "X Min"  # the quarter's plane x = 0: the half y >= 0
    half.CopyInput = 1
    half.UpdatePipeline(t)
    b = half.GetDataInformation().GetBounds()

    view = pc.white_view(ps, args.size, t)
    disp = ps.Show(half, view)
    disp.SetRepresentationType("Surface With Edges")
    disp.EdgeColor = [0.25, 0.25, 0.25]
    pc.colour_cells(ps, disp, view, "plastic_strain", "plastic strain", "Viridis (matplotlib)", args.range)
    pc.caption(ps, view, "%s   t = %.3g us   half model (the quarter and its mirror), cut y = 0, eroded "
               "elements hidden" % (os.path.basename(args.xmf), 1e6 * t))

    ps.Render(view)  # the first Render resets the camera: place it after that
    # Along +y at the cut, a little from below, z up; on the hole (x = 0, z = plate).
    span = 6.0e-3
    focus = [0.0, 0.5e-3, -2.0e-3]
    view.CameraViewUp = [0, 0, 1]
    view.CameraFocalPoint = focus
    view.CameraPosition = [focus[0] + 0.3 * span, focus[1] - 3.0 * span, focus[2] - 0.8 * span]
    view.CameraParallelProjection = 0
    view.CameraViewAngle = 30
    ps.Render(view)
    ok = pc.save(ps, view, args.out, args.size)
    del view
    print(json.dumps({"ok": ok, "time": t, "bounds": list(b), "png": args.out}))
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
