"""The plug leaving the plate: a picture of input/perforation.yaml's result on its
symmetry plane y = 0 (the quarter model's cut through the axis), eroded elements left
out (status 0), the live ones on their deformed places and coloured by their plastic
strain (docs/verification.md, "The perforated plate").

    ../shared/tools/paraview/run_pvpython.sh scripts/perforation_picture.py RESULT.xmf \\
        --time 6e-5 --out docs/figures/perforation_plug.png [--width 40e-3]
"""
import argparse

from paraview import simple as pv


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("xmf")
    p.add_argument("--time", type=float, required=True, help="the written step nearest this time (s)")
    p.add_argument("--out", required=True)
    p.add_argument("--width", type=float, default=40e-3, help="the part of the plate shown from the axis (m)")
    p.add_argument("--range", type=float, nargs=2, default=[0.0, 1.5], help="plastic strain colour range")
    args = p.parse_args()

    reader = pv.Xdmf3ReaderS(FileName=[args.xmf])
    times = list(reader.TimestepValues)
    shown = min(times, key=lambda t: abs(t - args.time))
    live = pv.Threshold(Input=reader, Scalars=["CELLS", "status"], LowerThreshold=0.5, UpperThreshold=1.5)
    moved = pv.WarpByVector(Input=live, Vectors=["POINTS", "displacement"], ScaleFactor=1.0)
    # the slab of elements next to the cut y = 0 (its first layer), as far as --width
    near = pv.Clip(Input=moved, ClipType="Box", Invert=1, Crinkleclip=1)
    near.ClipType.Position = [-1.0, -1e-6, -1.0]
    near.ClipType.Length = [1.0 + args.width, 0.3e-3, 2.0]

    view = pv.CreateView("RenderView")
    view.ViewSize = [1200, 800]
    if hasattr(view, "UseColorPaletteForBackground"):
        view.UseColorPaletteForBackground = 0
    view.Background = [1, 1, 1]
    view.OrientationAxesVisibility = 0
    view.ViewTime = shown
    shown_near = pv.Show(near, view)
    pv.ColorBy(shown_near, ("CELLS", "plastic_strain"))
    lut = pv.GetColorTransferFunction("plastic_strain")
    lut.ApplyPreset("Viridis (matplotlib)", True)
    lut.RescaleTransferFunction(args.range[0], args.range[1])
    shown_near.SetScalarBarVisibility(view, True)
    bar = pv.GetScalarBar(lut, view)
    bar.Title = "plastic strain"
    bar.ComponentTitle = ""
    bar.TitleColor = bar.LabelColor = [0, 0, 0]
    shown_near.EdgeColor = [0.2, 0.2, 0.2]
    shown_near.SetRepresentationType("Surface With Edges")
    text = pv.Text(Text=f"t = {shown * 1e6:.0f} us, the symmetry plane y = 0, eroded elements left out")
    shown_text = pv.Show(text, view)
    shown_text.Color = [0, 0, 0]
    shown_text.FontSize = 14
    shown_text.WindowLocation = "Upper Right Corner"
    view.CameraPosition = [0.5 * args.width, -0.2, -0.015]
    view.CameraFocalPoint = [0.5 * args.width, 0.0, -0.015]
    view.CameraViewUp = [0, 0, 1]
    view.CameraParallelProjection = 1
    pv.Render(view)
    view.CameraFocalPoint = [0.55 * args.width, 0.0, -0.016]
    view.CameraPosition = [0.55 * args.width, -0.2, -0.016]
    view.CameraParallelScale = 0.5 * args.width  # half the height shown, m
    pv.Render(view)
    pv.SaveScreenshot(args.out, view, ImageResolution=[1200, 800])
    print(f"{args.out}: t = {shown:.4g} s")


if __name__ == "__main__":
    main()
