#!/usr/bin/python3
"""VTK 9.1 baseline: 512x512 MIP of the Cranium CT with vtkFixedPointVolumeRayCastMapper and
vtkGPUVolumeRayCastMapper (MAXIMUM_INTENSITY blend), steady-state frame medians.

Needs Debian's python3-vtk9 and an X server (Xvfb):
    xvfb-run -s "-screen 0 1024x768x24" /usr/bin/python3 bench/vtk_mip.py data/cranium/matrix.dat
"""
import statistics
import sys
import time

import vtk

FRAMES, WARMUP, SIZE = 15, 3, 512


def reader(path):
    r = vtk.vtkImageReader()
    r.SetFileName(path)
    r.SetDataScalarTypeToShort()
    r.SetDataByteOrderToLittleEndian()
    r.SetNumberOfScalarComponents(1)
    r.SetDataExtent(0, 255, 0, 255, 0, 107)
    r.SetDataSpacing(0.9570312, 0.9570312, 1.5)
    r.Update()
    return r


def measure(mapper, source, view):
    mapper.SetInputConnection(source.GetOutputPort())
    mapper.SetBlendModeToMaximumIntensity()
    prop = vtk.vtkVolumeProperty()
    opacity = vtk.vtkPiecewiseFunction()
    opacity.AddPoint(-1024, 1.0)
    opacity.AddPoint(3071, 1.0)
    colour = vtk.vtkColorTransferFunction()
    colour.AddRGBPoint(-1024, 0, 0, 0)
    colour.AddRGBPoint(3071, 1, 1, 1)
    prop.SetScalarOpacity(opacity)
    prop.SetColor(colour)
    prop.SetInterpolationTypeToLinear()
    volume = vtk.vtkVolume()
    volume.SetMapper(mapper)
    volume.SetProperty(prop)
    ren = vtk.vtkRenderer()
    ren.AddVolume(volume)
    win = vtk.vtkRenderWindow()
    win.SetSize(SIZE, SIZE)
    win.AddRenderer(ren)
    win.SetOffScreenRendering(1)
    cam = ren.GetActiveCamera()
    cam.ParallelProjectionOn()
    ren.ResetCamera()
    cam.Azimuth(view[0])
    cam.Elevation(view[1])
    cam.OrthogonalizeViewUp()
    ren.ResetCamera()
    times = []
    for i in range(WARMUP + FRAMES):
        cam.Azimuth(0.01 if i % 2 else -0.01)  # a real camera change each frame, so nothing is cached
        t0 = time.perf_counter()
        win.Render()
        times.append((time.perf_counter() - t0) * 1000.0)
    renderer = win.ReportCapabilities().splitlines()
    gl = next((l for l in renderer if "OpenGL renderer" in l), "?").strip()
    win.Finalize()
    return statistics.median(times[WARMUP:]), gl


def main():
    source = reader(sys.argv[1] if len(sys.argv) > 1 else "data/cranium/matrix.dat")
    print(f"VTK {vtk.vtkVersion.GetVTKVersion()}, {SIZE}x{SIZE}, median of {FRAMES} frames after {WARMUP}")
    for name, make in (("fixed-point", vtk.vtkFixedPointVolumeRayCastMapper), ("gpu", vtk.vtkGPUVolumeRayCastMapper)):
        for view_name, view in (("anterior", (0, 0)), ("oblique", (30, 20))):
            ms, gl = measure(make(), source, view)
            print(f"| {name} | {view_name} | {ms:.1f} ms | {gl} |", flush=True)


if __name__ == "__main__":
    main()
