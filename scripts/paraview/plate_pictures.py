"""Pictures of a plate impact result with ParaView. Needs X: run it through
../shared/tools/paraview/run_pvpython.sh, which starts xvfb.

    run_pvpython.sh scripts/paraview/plate_pictures.py RESULT.xmf --out-dir DIR \
        [--prefix results_pv] [--range -6e7 6e7] [--scale 1000] [--time T]

Writes, at the last time (or --time):
  PREFIX_sigma_xx.png  the mesh warped by displacement x SCALE, coloured by stress XX
                       (Pa) with a fixed colour range, the z = 0 sample line drawn on it;
  PREFIX_line.png      ParaView's PlotOverLine along z = 0 (sigma_x* = sigma_x c1 / (lambda v0)
                       against x/d), with the exact step;
  PREFIX_line.csv      the samples of that line.
The line runs through cell interiors (y = z = h/2, h the y thickness of the
one-element-thick plates): a line on the cell faces samples whichever neighbour it hits.
Prints one JSON line; exit status 0 when both PNGs were written.
"""
import argparse
import json
import math
import os
import sys

# The case (../shared/reference/plate-impact.md).
E_MODULUS, POISSON, DENSITY, V0 = 2.1e11, 0.3, 7800.0, 1.0
LAMBDA = E_MODULUS * POISSON / ((1 + POISSON) * (1 - 2 * POISSON))
C1 = math.sqrt((LAMBDA + E_MODULUS / (1 + POISSON)) / DENSITY)
PLATEAU_X = -(1 - POISSON) / POISSON
FRONT_OVER_D = 0.56


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("xmf")
    p.add_argument("--out-dir", default=".")
    p.add_argument("--prefix", default="results_pv")
    p.add_argument("--range", type=float, nargs=2, default=[-6.0e7, 6.0e7], metavar=("MIN", "MAX"),
                   help="fixed colour range of stress XX in Pa")
    p.add_argument("--scale", type=float, default=1000.0, help="displacement warp factor")
    p.add_argument("--time", type=float, default=None)
    p.add_argument("--size", type=int, nargs=2, default=[1000, 560])
    args = p.parse_args()
    if not os.path.exists(args.xmf):
        print(json.dumps({"ok": False, "error": "file not found: %s" % args.xmf}))
        return 2
    import numpy as np
    import paraview.simple as ps
    from vtkmodules.util.numpy_support import vtk_to_numpy

    os.makedirs(args.out_dir, exist_ok=True)
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    import picture_common as pc

    xmf = os.path.abspath(args.xmf)
    reader, t = pc.read_at(ps, xmf, args.time)
    b = reader.GetDataInformation().GetBounds()
    h = b[3] - b[2]                      # one element thick in y: the element size
    d = max(-b[0], b[1])                 # plates from -d to 0 and 0 to d (or one plate)

    # --- the warped mesh coloured by sigma_xx ------------------------------------------
    warp = ps.WarpByVector(Input=reader)
    warp.Vectors = ["POINTS", "displacement"]
    warp.ScaleFactor = args.scale
    warp.UpdatePipeline(t)
    view = pc.white_view(ps, args.size, t)
    disp = ps.Show(warp, view)
    disp.SetRepresentationType("Surface")
    bar = pc.colour_cells(ps, disp, view, "stress", "stress XX (Pa)", "Cool to Warm", args.range, component=0)
    bar.RangeLabelFormat = "%-#6.2g"

    # Drawn in front of the mesh (y = -h) so that the camera sees it; sampled at y = h/2 below.
    line_src = ps.Line(Point1=[-d, -h, h / 2], Point2=[d, -h, h / 2])
    line_disp = ps.Show(line_src, view)
    line_disp.AmbientColor = line_disp.DiffuseColor = [0.0, 0.0, 0.0]
    line_disp.LineWidth = 3.0
    pc.caption(ps, view, "%s   t = %.4g s   displacement x %g   black line: PlotOverLine, z = h/2"
               % (os.path.basename(xmf), t, args.scale))

    ps.Render(view)   # the first Render resets the camera: place it after that
    # Look along +y at the x-z plane, z up, parallel projection framing the plates.
    view.CameraParallelProjection = 1
    view.CameraViewUp = [0, 0, 1]
    centre_x = 0.5 * (b[0] + b[1]) + 0.12 * d     # the plates left of centre, the colour bar right
    view.CameraFocalPoint = [centre_x, 0.0, 0.5 * d]
    view.CameraPosition = [centre_x, -10 * d, 0.5 * d]
    view.CameraParallelScale = 0.8 * d
    ps.Render(view)
    png_field = os.path.join(args.out_dir, args.prefix + "_sigma_xx.png")
    pc.save(ps, view, png_field, args.size)
    del view

    # --- PlotOverLine along z = 0 --------------------------------------------------------
    pol = ps.PlotOverLine(Input=reader)
    pol.Point1 = [-d + 1e-3 * h, h / 2, h / 2]
    pol.Point2 = [d - 1e-3 * h, h / 2, h / 2]
    pol.SamplingPattern = "Sample At Segment Centers"
    pol.UpdatePipeline(t)
    out = pol.GetClientSideObject().GetOutputDataObject(0)
    if out.IsA("vtkCompositeDataSet"):
        merged = ps.MergeBlocks(Input=pol)
        merged.UpdatePipeline(t)
        out = merged.GetClientSideObject().GetOutputDataObject(0)
    pd = out.GetPointData()
    pts = vtk_to_numpy(out.GetPoints().GetData())
    mask = vtk_to_numpy(pd.GetArray("vtkValidPointMask")).astype(bool)
    stress = vtk_to_numpy(pd.GetArray("stress")).reshape(len(pts), -1)
    x = pts[mask, 0]
    sx = stress[mask, 0] * C1 / (LAMBDA * V0)
    csv = os.path.join(args.out_dir, args.prefix + "_line.csv")
    np.savetxt(csv, np.column_stack([x, stress[mask, 0], sx]), delimiter=",",
               header="x,stress_xx,sigma_x_star", comments="", fmt="%.17g")

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(7.0, 3.6), dpi=100)
    ax.plot(x / d, sx, color="C0", lw=1.2, label="ParaView PlotOverLine, z = h/2")
    xe = np.array([-1, -FRONT_OVER_D, -FRONT_OVER_D, FRONT_OVER_D, FRONT_OVER_D, 1])
    ye = np.array([0, 0, PLATEAU_X, PLATEAU_X, 0, 0])
    if b[1] <= 1e-12 * d:   # one plate (reference): only x < 0
        xe, ye = xe[:3].tolist() + [0.0], ye[:3].tolist() + [PLATEAU_X]
    ax.plot(xe, ye, "k--", lw=1, label="exact")
    ax.set_xlabel("x / d")
    ax.set_ylabel(r"$\sigma_x^* = \sigma_x c_1 / (\lambda v_0)$")
    ax.set_title("%s, t = %.4g s" % (os.path.basename(xmf), t), fontsize=10)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, loc="lower center")
    fig.tight_layout()
    png_line = os.path.join(args.out_dir, args.prefix + "_line.png")
    fig.savefig(png_line)
    plt.close(fig)

    ok = all(os.path.exists(f) and os.path.getsize(f) > 0 for f in (png_field, png_line))
    print(json.dumps({"ok": ok, "time": t, "h": h, "d": d, "samples": int(mask.sum()),
                      "png": [png_field, png_line], "csv": csv}))
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
