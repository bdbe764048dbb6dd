"""A picture of the crushed tube (input/tube_crush.yaml, a quarter model) with ParaView.
Needs X: run it through ../shared/tools/paraview/run_pvpython.sh, which starts xvfb.

    run_pvpython.sh scripts/paraview/tube_picture.py RESULT.xmf --out PNG [--time T]

At the last time (or --time): the quarter reflected across x = 0 into the half tube
y >= 0, warped by the displacement (x 1), coloured by the equivalent plastic strain,
seen along +y so that the cut y = 0 shows the wall's section folded in concertina.
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
    p.add_argument("--range", type=float, nargs=2, default=[0.0, 1.0], metavar=("MIN", "MAX"),
                   help="colour range of the plastic strain")
    p.add_argument("--size", type=int, nargs=2, default=[900, 800])
    args = p.parse_args()
    if not os.path.exists(args.xmf):
        print(json.dumps({"ok": False, "error": "file not found: %s" % args.xmf}))
        return 2
    import paraview.simple as ps

    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    import picture_common as pc

    reader, t = pc.read_at(ps, args.xmf, args.time)
    warp = ps.WarpByVector(Input=reader)
    warp.Vectors = ["POINTS", "displacement"]
    warp.ScaleFactor = 1.0
    half = ps.Reflect(Input=warp)
    half.Plane = "X Min"   # the quarter's plane x = 0: the half tube y >= 0
    half.CopyInput = 1
    half.UpdatePipeline(t)
    b = half.GetDataInformation().GetBounds()

    view = pc.white_view(ps, args.size, t)
    disp = ps.Show(half, view)
    disp.SetRepresentationType("Surface With Edges")
    disp.EdgeColor = [0.25, 0.25, 0.25]
    pc.colour_cells(ps, disp, view, "plastic_strain", "plastic strain", "Viridis (matplotlib)", args.range)
    pc.caption(ps, view, "%s   t = %.4g ms   half tube (the quarter and its mirror), cut y = 0"
               % (os.path.basename(args.xmf), 1e3 * t))

    ps.Render(view)  # the first Render resets the camera: place it after that
    # Along +y at the cut, a little from above, z up.
    cx, cz = 0.5 * (b[0] + b[1]), 0.5 * (b[4] + b[5])
    span = max(b[1] - b[0], b[5] - b[4])
    view.CameraViewUp = [0, 0, 1]
    view.CameraFocalPoint = [cx, 0.3 * b[3], cz]
    view.CameraPosition = [cx + 0.5 * span, -3.0 * span, cz + 0.8 * span]
    view.CameraParallelProjection = 0
    ps.ResetCamera(view)
    view.CameraPosition = [cx + 0.5 * span, -3.0 * span, cz + 0.8 * span]
    view.CameraViewAngle = 22
    ps.Render(view)
    ok = pc.save(ps, view, args.out, args.size)
    del view
    print(json.dumps({"ok": ok, "time": t, "bounds": list(b), "png": args.out}))
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
