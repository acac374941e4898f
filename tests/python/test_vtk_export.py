"""export --format vtu read back with VTK's own readers (from Debian's python3-paraview, which conflicts with python3-vtk9: ParaView's own VTK)."""
import os
import subprocess
import xml.etree.ElementTree as ET

import pytest

import siloscope

vtk = pytest.importorskip("vtk", reason="VTK's Python modules (python3-paraview, installed by .ci/test) are needed to read the export")


def read_grid(path):
    reader = vtk.vtkXMLUnstructuredGridReader()
    reader.SetFileName(str(path))
    reader.Update()
    return reader.GetOutput()


def test_vtk_reads_the_export(recording, binary, tmp_path):
    out = tmp_path / "vtu"
    done = subprocess.run([binary, "export", str(recording), "--format", "vtu", "--frames", "10:20", "--out",
                           str(out)], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    tr = siloscope.read_trajectory(str(recording))
    # The time series: two parts (grains, walls) at every frame's time.
    pvd = ET.parse(out / "trajectory.pvd").getroot()
    sets = pvd.find("Collection").findall("DataSet")
    grains = [d for d in sets if d.get("part") == "0"]
    assert len(grains) == 11
    # Each frame: grains, walls, the arch and the force chains (record keeps the contacts), each its own block.
    assert {d.get("part") for d in sets} == {"0", "1", "3", "4"} and len(sets) == 4 * 11
    assert abs(float(grains[5].get("timestep")) - float(tr.t[15])) < 1e-6
    g = read_grid(out / grains[5].get("file"))
    assert g.GetNumberOfPoints() == 250 and g.GetNumberOfCells() == 250
    x, y, z = g.GetPoint(7)
    assert abs(x - tr.x[15, 7]) < 1e-6 and abs(y - tr.y[15, 7]) < 1e-6 and z == 0
    pd = g.GetPointData()
    assert abs(pd.GetArray("radius").GetValue(0) - 0.065) < 1e-7
    assert abs(pd.GetArray("radius").GetValue(249) - 0.026) < 1e-7
    assert pd.GetArray("velocity").GetNumberOfComponents() == 3
    assert sum(pd.GetArray("species").GetValue(i) for i in range(250)) == 100
    assert sum(pd.GetArray("arch").GetValue(i) for i in range(250)) == len(tr.arch(15))
    assert abs(g.GetFieldData().GetArray("TimeValue").GetValue(0) - tr.t[15]) < 1e-6
    walls = read_grid(out / "walls.vtu")
    assert walls.GetNumberOfCells() == 5  # two hopper walls, two silo walls, the top
    bounds = walls.GetBounds()
    assert abs(bounds[0] + 0.5) < 1e-6 and abs(bounds[1] - 0.5) < 1e-6 and abs(bounds[3] - 6.36) < 1e-6
    print(f"VTK {vtk.vtkVersion.GetVTKVersion()}: {len(grains)} frames, 250 grains, point 7 at ({x:.4f}, {y:.4f}), "
          f"radius 0.065, t = {float(grains[5].get('timestep')):.3f} s; walls {walls.GetNumberOfCells()} lines")


def test_vtu_of_a_flat_silo_with_an_obstacle_and_pentagons(binary, root, tmp_path):
    rec = tmp_path / "pent"
    subprocess.run([binary, "record", os.path.join(root, "assets/scenes/pentagons.toml"), "--duration", "1",
                    "--set", "settle_time=1", "--set", "obstacle=bar", "--set", "obstacle_size=0.3", "--set",
                    "obstacle_thickness=0.05", "--set", "obstacle_height=0.6", "--size", "320x240", "--fps", "10",
                    "--quiet", "--out", str(rec)], check=True)
    subprocess.run([binary, "export", str(rec), "--format", "vtu"], check=True, capture_output=True)
    g = read_grid(rec / "vtu" / "grains_000005.vtu")
    assert g.GetPointData().GetArray("sides").GetValue(0) == 5
    assert g.GetPointData().GetArray("extent").GetValue(0) > g.GetPointData().GetArray("radius").GetValue(0)
    walls = read_grid(rec / "vtu" / "walls.vtu")
    assert walls.GetNumberOfCells() == 5  # five walls; the bar is a block of its own
    obstacle = read_grid(rec / "vtu" / "obstacle.vtu")
    assert obstacle.GetNumberOfCells() == 1 and obstacle.GetCellType(0) == 7 and obstacle.GetNumberOfPoints() == 4


def test_binary_is_the_default_and_holds_what_ascii_holds(recording, binary, tmp_path):
    # Binary (appended raw, zlib) by default; --vtu-encoding ascii gives the same values, several times larger;
    # every frame names its species.
    files = {}
    for enc in ("binary", "ascii"):
        out = tmp_path / enc
        subprocess.run([binary, "export", str(recording), "--format", "vtu", "--frames", "5:9", "--vtu-encoding", enc,
                        "--out", str(out)], check=True, capture_output=True)
        files[enc] = out
    head = (files["binary"] / "grains_000007.vtu").read_bytes()[:400].decode("latin-1")
    assert 'compressor="vtkZLibDataCompressor"' in head
    assert 'format="ascii"' in (files["ascii"] / "grains_000007.vtu").read_text()[:2000]
    size = {k: sum(f.stat().st_size for f in v.glob("grains_*.vtu")) for k, v in files.items()}
    assert size["binary"] * 2 < size["ascii"]
    b, a = read_grid(files["binary"] / "grains_000007.vtu"), read_grid(files["ascii"] / "grains_000007.vtu")
    for name in ("radius", "force", "species", "arch", "angle"):
        xb, xa = b.GetPointData().GetArray(name), a.GetPointData().GetArray(name)
        assert all(abs(xb.GetValue(i) - xa.GetValue(i)) <= 1e-6 * max(1.0, abs(xa.GetValue(i)))
                   for i in range(250)), name
    names = b.GetFieldData().GetAbstractArray("SpeciesNames")
    assert [names.GetValue(i) for i in range(names.GetNumberOfValues())] == ["original", "added"]
    bad = subprocess.run([binary, "export", str(recording), "--format", "vtu", "--vtu-encoding", "base64", "--out",
                          str(tmp_path / "x")], capture_output=True, text=True)
    assert bad.returncode == 2 and "binary" in bad.stderr and "ascii" in bad.stderr
