"""What the pictures of scripts/paraview share: a result read at a time, a white view,
cells coloured by a field with a fixed range, a caption, the PNG written. Call with
paraview.simple as `ps` (imported by the caller, under pvpython)."""
import os


def read_at(ps, xmf, time):
    """The XDMF result's reader, updated at the written time nearest `time` (None: the
    last), and that time."""
    reader = ps.Xdmf3ReaderS(FileName=[os.path.abspath(xmf)])
    reader.UpdatePipelineInformation()
    times = [float(t) for t in (reader.TimestepValues or [0.0])]
    t = times[-1] if time is None else min(times, key=lambda x: abs(x - time))
    reader.UpdatePipeline(t)  # explicitly, or downstream filters may come out empty
    return reader, t


def white_view(ps, size, t):
    """A render view of `size` pixels at time t on white, with the orientation axes."""
    view = ps.CreateView("RenderView")
    view.ViewSize = list(size)
    view.ViewTime = t
    view.OrientationAxesVisibility = 1
    try:
        view.UseColorPaletteForBackground = 0
    except AttributeError:
        pass
    view.Background = [1.0, 1.0, 1.0]
    return view


def colour_cells(ps, disp, view, field, title, preset, value_range, component=None):
    """Colours `disp` by cell field `field` (its component index `component`, or the
    field itself) over the fixed range, with a scalar bar titled `title`; the bar."""
    if component is None:
        ps.ColorBy(disp, ("CELLS", field))
    else:
        ps.ColorBy(disp, ("CELLS", field, "XX" if component == 0 else str(component)))
    lut = ps.GetColorTransferFunction(field)
    if component is not None:
        lut.VectorMode = "Component"
        lut.VectorComponent = component
    lut.ApplyPreset(preset, True)
    lut.RescaleTransferFunction(value_range[0], value_range[1])
    lut.AutomaticRescaleRangeMode = "Never"
    disp.SetScalarBarVisibility(view, True)
    bar = ps.GetScalarBar(lut, view)
    bar.Title = title
    bar.ComponentTitle = ""
    bar.TitleColor = bar.LabelColor = [0.0, 0.0, 0.0]
    bar.TitleFontSize = bar.LabelFontSize = 14
    return bar


def caption(ps, view, text):
    """Black text in the view's upper left corner."""
    shown = ps.Show(ps.Text(Text=text), view)
    shown.Color = [0.0, 0.0, 0.0]
    shown.FontSize = 14
    shown.WindowLocation = "Upper Left Corner"


def save(ps, view, out, size):
    """The view as a PNG at `out`; deletes the view. Whether the file was written."""
    os.makedirs(os.path.dirname(os.path.abspath(out)), exist_ok=True)
    ps.SaveScreenshot(out, view, ImageResolution=list(size))
    ps.Delete(view)  # before teardown: a view left to exit gives GLXBadContext under Xvfb
    return os.path.exists(out) and os.path.getsize(out) > 0
