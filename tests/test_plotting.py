"""Pictures: every bundled mechanism is drawn, and what is drawn is read back from the artists.

The freedoms and constraints drawn on the end effector are compared with the
loop-closure route (:func:`mobility.core.loop_closure.loop_closure`), not with the
analysis that produced them: translation arrows must span the pure
translations of the end effector's twist system, each rotation axis (with its
written pitch) must be a twist of it, each force line and couple must be
reciprocal to it.
"""

from __future__ import annotations

import re
import subprocess
import sys
from collections import Counter
from pathlib import Path

import matplotlib
import numpy as np
import pytest

from mobility.errors import PlotFormatError, PlottingUnavailableError

matplotlib.use("Agg")

from builders import THREE_RPS_YAML  # noqa: E402
from matplotlib.backends.backend_agg import FigureCanvasAgg  # noqa: E402

import mobility  # noqa: E402
from mobility.cli import main  # noqa: E402
from mobility.core.joint_screws import joint_screws  # noqa: E402
from mobility.core.loop_closure import loop_closure  # noqa: E402
from mobility.report.plotting import (  # noqa: E402
    COLORS,
    choose_views,
    plot_graph,
    plot_mechanism,
    save_figure,
    sketch,
)
from mobility.core.result import NodeSystem  # noqa: E402
from mobility.core.screws import free_vector_subspace  # noqa: E402
from mobility.core.topology import JointNode, Parallel, Series, decompose  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
BUNDLED = sorted((ROOT / "mechanisms").glob("*.yaml"))

RPS = THREE_RPS_YAML

SCREW_ARM = """
name: helical, cylindrical and universal
ground: g
end_effector: tool
joints:
  - {name: H1, type: H, links: [g, nut], axis: [0, 0, 1], point: [1, 2, 0], pitch: 0.25}
  - {name: C1, type: C, links: [nut, arm], axis: [1, 0, 0], point: [1, 2, 1]}
  - {name: U1, type: U, links: [arm, tool], axes: [[0, 1, 0], [0, 0, 1]], point: [2, 2, 1]}
"""

PLANAR_PAIR = """
name: planar pair and a slider
ground: g
end_effector: top
joints:
  - {name: E1, type: E, links: [g, puck], normal: [0, 0, 1]}
  - {name: P1, type: P, links: [puck, top], axis: [0, 0, 1]}
"""

PRS = """
name: 3-PRS
ground: base
end_effector: platform
parameters: {rb: 2, rp: 1, h: 1}
limbs:
  - copies: 3
    joints:
      - {name: "P{i+1}", type: P, links: [base, "slider{i+1}"], axis: [0, 0, 1]}
      - {name: "R{i+1}", type: R, links: ["slider{i+1}", "leg{i+1}"], axis: ["-sind(120*i)", "cosd(120*i)", 0],
         point: ["rb*cosd(120*i)", "rb*sind(120*i)", 0.5]}
      - {name: "S{i+1}", type: S, links: ["leg{i+1}", platform], point: ["rp*cosd(120*i)", "rp*sind(120*i)", "h+0.5"]}
"""

INLINE = {"3rps": RPS, "screw_arm": SCREW_ARM, "planar_pair": PLANAR_PAIR}
CASES = [pytest.param(p, id=p.stem) for p in BUNDLED] + [pytest.param(v, id=k) for k, v in INLINE.items()]


def load(source) -> mobility.Mechanism:
    return mobility.load(source) if isinstance(source, Path) else mobility.loads(source)


def drawn(ax, kind: str) -> dict[int, np.ndarray]:
    """3D polylines of an axes whose gid is ``mobility:<kind>:<i>``, by index."""
    out = {}
    for line in ax.get_lines():
        m = re.fullmatch(rf"mobility:{kind}:(\d+)", line.get_gid() or "")
        if m:
            out[int(m.group(1))] = np.column_stack(line.get_data_3d())
    return out


def texts(ax, prefix: str) -> list:
    return [t for t in ax.texts if (t.get_gid() or "").startswith(prefix)]


def pitch_of(label: str) -> float:
    m = re.search(r"h = (\S+)", label)
    return float(m.group(1)) if m else 0.0


def line_screw(seg: np.ndarray, pitch: float) -> np.ndarray:
    d = seg[-1] - seg[0]
    d = d / np.linalg.norm(d)
    p = seg.mean(axis=0)
    return np.concatenate([d, np.cross(p, d) + pitch * d])


def residual_from_span(screw: np.ndarray, basis: np.ndarray) -> float:
    """Distance of a unit screw (normalised coordinates) from the span of orthonormal ``basis``."""
    s = screw / np.linalg.norm(screw)
    return float(np.linalg.norm(s - basis @ (basis.T @ s))) if basis.size else float(np.linalg.norm(s))


def pixels(fig, first_only: bool = False) -> np.ndarray:
    """The figure rendered by Agg at a low resolution (only its first axes when asked: 3D drawing is slow)."""
    for ax in fig.axes[1:]:
        ax.set_visible(not first_only)
    canvas = FigureCanvasAgg(fig)
    fig.set_dpi(30)
    canvas.draw()
    return np.asarray(canvas.buffer_rgba())[..., :3].astype(int)


def near_colour(img: np.ndarray, hex_colour: str, tol: int = 40) -> int:
    rgb = np.array([int(hex_colour[k : k + 2], 16) for k in (1, 3, 5)])
    return int(np.sum(np.all(np.abs(img - rgb) < tol, axis=-1)))


@pytest.mark.parametrize("source", CASES)
def test_drawn_freedoms_and_constraints_match_the_loop_closure_route(source):
    m = load(source)
    r = mobility.analyze(m)
    lc = loop_closure(m)
    norm = joint_screws(m).normalisation
    twists = lc.end_effector_twists  # orthonormal, normalised coordinates
    free, _, _ = free_vector_subspace(twists) if twists.shape[1] else (np.zeros((3, 0)), None, None)
    fig = plot_mechanism(m, r, constraints=True, views=1)  # one chosen view (two: see test_views_draw_the_same_scene)
    assert len(fig.axes) == 1
    world = m.world_joints
    ee_points = np.array([j.point for j in world if m.end_effector in j.links and j.point is not None]).reshape(-1, 3)
    for ax in fig.axes:
        # translations: one arrow per pure translation, from the end effector's centre, spanning them
        arrows = drawn(ax, "translation")
        assert len(arrows) == free.shape[1]
        if arrows:
            dirs = np.array([a[-1] - a[0] for a in arrows.values()]).T
            assert np.linalg.matrix_rank(dirs, tol=1e-9 * np.abs(dirs).max()) == free.shape[1]
            # compare as subspaces: the drawn directions lie in the free-vector subspace and span it
            dirs = dirs / np.linalg.norm(dirs, axis=0)
            assert np.allclose(free @ (free.T @ dirs), dirs, atol=1e-9)
            if len(ee_points):
                for a in arrows.values():
                    assert np.allclose(a[0], ee_points.mean(axis=0))
        # rotations: each axis line, with the pitch written beside it, is a twist of the end effector
        axes = drawn(ax, "rotation-axis")
        labels = {int(t.get_gid().rsplit(":", 1)[1]): t.get_text() for t in texts(ax, "mobility:rotation-label:")}
        assert len(axes) == r.dof - free.shape[1] == len(labels)
        drawn_twists = [np.concatenate([np.zeros(3), (a[-1] - a[0]) / np.linalg.norm(a[-1] - a[0])]) for a in arrows.values()]
        for i, seg in axes.items():
            h = pitch_of(labels[i])
            tw = norm.from_world(line_screw(seg, h)).ravel()
            assert residual_from_span(tw, twists) < (2e-3 if h else 1e-7), labels[i]
            drawn_twists.append(tw)
            assert ("h = " in labels[i]) == (r.rotations[i].pitch != 0)
        if drawn_twists:
            assert np.linalg.matrix_rank(np.array(drawn_twists).T, tol=1e-3) == r.dof
        # constraints: force lines and couples are reciprocal to every end-effector twist
        forces = drawn(ax, "force")
        couples = drawn(ax, "couple")
        flabels = {int(t.get_gid().rsplit(":", 1)[1]): t.get_text() for t in texts(ax, "mobility:force-label:")}
        assert len(forces) + len(couples) == 6 - r.dof
        wrenches = []
        for i, seg in forces.items():
            wrenches.append(norm.from_world(line_screw(seg, pitch_of(flabels[i]))).ravel())
        for seg in couples.values():
            wrenches.append(np.concatenate([np.zeros(3), (seg[-1] - seg[0]) / np.linalg.norm(seg[-1] - seg[0])]))
        if wrenches:
            w = np.array(wrenches).T
            w = w / np.linalg.norm(w, axis=0)
            if twists.size:
                swapped = np.vstack([w[3:], w[:3]])
                assert np.max(np.abs(swapped.T @ twists)) < 2e-3
            assert np.linalg.matrix_rank(w, tol=1e-3) == 6 - r.dof
        # joints: one marker per joint, at the file's point when it has one
        by_type = Counter(j.type for j in world)
        for coll in ax.collections:
            gid = coll.get_gid() or ""
            if gid.startswith("mobility:joints:"):
                t = gid.rsplit(":", 1)[1]
                offsets = np.column_stack(coll._offsets3d)
                assert len(offsets) == by_type.pop(t)
                located = np.array([j.point for j in world if j.type == t and j.point is not None]).reshape(-1, 3)
                for p in located:
                    assert np.min(np.linalg.norm(offsets - p, axis=1)) < 1e-9 * (1 + np.abs(p).max())
        assert not by_type, f"joint types not drawn: {by_type}"
        # links: every link with two distinct joint places is drawn
        sk = sketch(m)
        gids = {a.get_gid() for a in ax.get_children()}
        for link, idx in sk.link_joints.items():
            spread = np.ptp(sk.points[list(idx)], axis=0).max()
            if spread > 1e-6 * sk.size:
                assert f"mobility:link:{link}" in gids, link
    img = pixels(fig)
    assert (img.min(axis=-1) < 200).mean() > 0.01, "picture is blank"
    assert (near_colour(img, COLORS["translation"]) > 0) == bool(free.shape[1])
    assert near_colour(img, COLORS["end_effector"]) > 0


def test_views_draw_the_same_scene_from_different_sides():
    m = mobility.loads(RPS)
    fig = plot_mechanism(m, constraints=True, views=3)
    assert len(fig.axes) == 3
    eyes = []
    for ax in fig.axes:
        e, a = np.radians(ax.elev), np.radians(ax.azim)
        eyes.append([np.cos(e) * np.cos(a), np.cos(e) * np.sin(a), np.sin(e)])
        for kind in ("translation", "rotation-axis", "force", "couple"):
            first, this = drawn(fig.axes[0], kind), drawn(ax, kind)
            assert first.keys() == this.keys() and all(np.allclose(first[k], this[k]) for k in first)
    eyes = np.array(eyes)
    cos = eyes @ eyes.T
    assert np.all(cos[np.triu_indices(3, 1)] < np.cos(np.radians(60)) + 1e-9)  # at least 60 degrees apart
    assert (pixels(fig).min(axis=-1) < 200).mean() > 0.01


def _tree_nodes(node):
    yield node
    children = [c for _, _, c in node.edges] if hasattr(node, "edges") else getattr(node, "children", ())
    for c in children:
        yield from _tree_nodes(c)


@pytest.mark.parametrize("source", CASES)
def test_graph_picture_shows_every_joint_and_the_tree(source):
    m = load(source)
    r = mobility.analyze(m)
    fig = plot_graph(m, r)
    ax_g, ax_t = fig.axes
    edge_gids = {a.get_gid() for a in ax_g.get_children() if (a.get_gid() or "").startswith("mobility:graph:joint:")}
    assert edge_gids == {f"mobility:graph:joint:{j.name}" for j in m.joints}
    topo = decompose(m)
    nodes = [n for root in (topo.root, *topo.detached) for n in _tree_nodes(root)]
    kinds = Counter(type(n).__name__ for n in nodes)
    drawn_kinds = Counter(t.get_gid().rsplit(":", 1)[1] for t in texts(ax_t, "mobility:tree:"))
    assert drawn_kinds["joint"] == kinds["JointNode"] == len(m.joints)
    assert drawn_kinds["series"] == kinds["Series"]
    assert drawn_kinds["parallel"] == kinds["Parallel"]
    assert drawn_kinds["bridge"] == kinds["Bridge"]
    leaves = sorted(t.get_text().split("\n")[0] for t in texts(ax_t, "mobility:tree:joint"))
    assert leaves == sorted(j.name for j in m.joints)
    # series of joints only: its dimension is the rank of the joint twists, computed here directly
    js = joint_screws(m)
    drawn_series = Counter(t.get_text().split("\n")[1] for t in texts(ax_t, "mobility:tree:series"))
    for n in nodes:
        if isinstance(n, Series) and all(isinstance(c, JointNode) for c in n.children):
            cols = np.hstack([js.of_joint(c.index) for c in n.children])
            rank = int(np.linalg.matrix_rank(cols, tol=1e-8))
            idle = cols.shape[1] - rank
            label = f"dim {rank}" + (f", idle {idle}" if idle else "")
            assert drawn_series[label] > 0, label
            drawn_series[label] -= 1
    # the top of the tree: the end effector's DOF by the independent route
    lc = loop_closure(m)
    top = [t for t in ax_t.texts if t.get_text().startswith("end effector:")]
    assert len(top) == 1 and top[0].get_text().startswith(f"end effector: {lc.end_effector_twists.shape[1]} DOF")
    assert isinstance(topo.root, Parallel) == any(t.get_text().startswith("∥") and t.get_position() == top[0].xy for t in texts(ax_t, "mobility:tree:"))


def test_graph_picture_draws_the_values_the_analysis_found():
    """The tree is labelled from ``Result.node_systems``: no screw system is evaluated again for the picture."""
    m = mobility.loads(RPS)
    r = mobility.analyze(m)

    class Shifted:  # the result, with every node's idle count raised by 7
        node_systems = {n: NodeSystem(s.dof, s.idle + 7) for n, s in r.node_systems.items()}

        def __getattr__(self, name):
            return getattr(r, name)

    def labels(result):
        drawn = texts(plot_graph(m, result).axes[1], "mobility:tree:")
        return sorted(t.get_text().split("\n")[1] for t in drawn if not t.get_gid().endswith(":joint"))

    assert labels(r) == sorted(f"dim {s.dof}" + (f", idle {s.idle}" if s.idle else "") for n, s in r.node_systems.items() if not isinstance(n, JointNode))
    assert labels(Shifted()) == sorted(f"dim {s.dof}, idle {s.idle + 7}" for n, s in r.node_systems.items() if not isinstance(n, JointNode))


def test_graph_picture_is_not_blank_and_colours_the_limbs():
    fig = plot_graph(mobility.loads(RPS))
    img = pixels(fig)
    assert (img.min(axis=-1) < 200).mean() > 0.01
    for colour in ("#1f77b4", "#d62728", "#2ca02c"):  # three limbs, three colours
        assert near_colour(img, colour, tol=25) > 20


def test_prismatic_joints_are_placed_beside_their_located_neighbour():
    m = mobility.loads(PRS)
    sk = sketch(m)
    for i in range(3):
        p = sk.points[sk.names.index(f"P{i + 1}")]
        rpt = sk.points[sk.names.index(f"R{i + 1}")]
        # below the R joint (away from the platform), along the P axis, a quarter of the scene
        assert np.allclose(p, rpt - [0, 0, 0.25 * sk.size])
        assert not sk.located[sk.names.index(f"P{i + 1}")]
    rps = mobility.loads(RPS)
    sk = sketch(rps)
    # between the R and the S of its limb: both of its links have located joints
    assert np.allclose(sk.points[sk.names.index("P1")], (sk.points[sk.names.index("R1")] + sk.points[sk.names.index("S1")]) / 2)


def test_views_avoid_overlap_and_end_on_directions():
    pts = np.array([[0.0, 0, 0], [1, 0, 0], [2, 0, 0], [2, 1, 0.5]])
    views = choose_views(pts, np.array([[1.0, 0, 0], [0, 0, 1]]), 2.0, count=2)
    assert len(views) == 2
    for elev, azim in views:
        e, a = np.radians(elev), np.radians(azim)
        eye = np.array([np.cos(e) * np.cos(a), np.cos(e) * np.sin(a), np.sin(e)])
        for d in ([1.0, 0, 0], [0, 0, 1]):
            assert np.sqrt(1 - (eye @ d) ** 2) >= 0.35  # neither direction seen end-on
        proj = pts - np.outer(pts @ eye, eye)
        gaps = [np.linalg.norm(proj[i] - proj[j]) for i in range(4) for j in range(i)]
        assert min(gaps) > 0.04 * 2.0
    (e1, a1), (e2, a2) = views
    eyes = [np.array([np.cos(np.radians(e)) * np.cos(np.radians(a)), np.cos(np.radians(e)) * np.sin(np.radians(a)), np.sin(np.radians(e))]) for e, a in views]
    assert eyes[0] @ eyes[1] < np.cos(np.radians(60)) + 1e-9


def test_helical_pitch_is_written_with_its_unit():
    m = mobility.loads(SCREW_ARM.replace("ground: g", "ground: g\nunits: {length: mm}").replace("end_effector: tool", "end_effector: nut"))
    r = mobility.analyze(m)
    fig = plot_mechanism(m, r, views=[(30, 40)])
    labels = [t.get_text() for t in texts(fig.axes[0], "mobility:rotation-label:")]
    helical = [a for a in r.rotations if a.pitch != 0]
    assert len([s for s in labels if "mm/rad" in s]) == len(helical) > 0
    assert fig.axes[0].elev == 30 and fig.axes[0].azim == 40


@pytest.mark.parametrize("suffix,magic", [(".png", b"\x89PNG"), (".svg", b"<?xml"), (".pdf", b"%PDF")])
def test_cli_writes_each_format(tmp_path, capsys, suffix, magic):
    src = tmp_path / "rps.yaml"
    src.write_text(RPS)
    out = tmp_path / f"rps{suffix}"
    args = ["plot", str(src), "-o", str(out), "--dpi", "40"] + (["--constraints"] if suffix == ".svg" else []) + (["--graph"] if suffix == ".pdf" else [])
    assert main(args) == 0
    assert out.read_bytes()[:5].startswith(magic)
    assert "wrote" in capsys.readouterr().out


def test_cli_refuses_an_unknown_picture_type(tmp_path, capsys):
    src = tmp_path / "rps.yaml"
    src.write_text(RPS)
    assert main(["plot", str(src), "-o", str(tmp_path / "x.jpg")]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "x.jpg" in err and ".png" in err
    with pytest.raises(PlotFormatError):
        save_figure(plot_graph(mobility.loads(RPS)), tmp_path / "y.gif")
    flexure = ROOT / "examples" / "flexure" / "three_rod.yaml"
    if flexure.exists():  # a flexure document is named as such, not reported as a bad mechanism file
        assert main(["plot", str(flexure), "-o", str(tmp_path / "f.png")]) == 2
        err = capsys.readouterr().err
        assert err.count("\n") == 1 and "flexure document" in err
        assert not (tmp_path / "f.png").exists()


def test_missing_matplotlib_is_one_line_with_the_install_hint(tmp_path, capsys, monkeypatch):
    src = tmp_path / "rps.yaml"
    src.write_text(RPS)
    for name in ("matplotlib", "matplotlib.figure", "mpl_toolkits", "mpl_toolkits.mplot3d"):
        monkeypatch.setitem(sys.modules, name, None)  # import raises ImportError
    with pytest.raises(PlottingUnavailableError, match=re.escape("pip install 'mechanism-mobility[plot]'")):
        plot_mechanism(mobility.loads(RPS))
    out = tmp_path / "x.png"
    assert main(["plot", str(src), "-o", str(out)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "pip install 'mechanism-mobility[plot]'" in err and "Traceback" not in err
    assert not out.exists()
    assert issubclass(PlottingUnavailableError, mobility.MobilityError)


def test_the_core_imports_and_analyses_without_matplotlib(tmp_path):
    src = tmp_path / "rps.yaml"
    src.write_text(RPS)
    code = f"""
import sys
class Block:
    def find_spec(self, name, path=None, target=None):
        if name.split('.')[0] in ('matplotlib', 'mpl_toolkits'):
            raise ImportError(f"No module named {{name!r}}", name=name)
sys.meta_path.insert(0, Block())
import mobility, mobility.report.plotting, mobility.report.markdown
from mobility.cli import main
assert main(['analyze', {str(src)!r}, '--format', 'md']) == 0
assert 'matplotlib' not in sys.modules
print('STATUS', main(['plot', {str(src)!r}, '-o', {str(tmp_path / 'x.png')!r}]))
"""
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60)
    assert done.returncode == 0, done.stderr
    assert "STATUS 2" in done.stdout
    assert done.stderr.strip() == "mobility: plotting needs matplotlib, which is not installed: pip install 'mechanism-mobility[plot]'"


# -- any size, any scale ----------------------------------------------------------------------------


def ladder(triangles: int) -> mobility.Mechanism:
    z = (0.0, 0.0, 1.0)
    joints = [mobility.Joint(f"A{i}", "R", ("g", f"l{i}"), axis=z, point=(float(i), 0.0, 0.0)) for i in range(triangles + 1)]
    joints += [mobility.Joint(f"B{i}", "R", (f"l{i}", f"l{i + 1}"), axis=z, point=(i + 0.5, 1.0 + 0.25 * np.sin(i), 0.0)) for i in range(triangles)]
    return mobility.Mechanism(f"ladder of {triangles}", "g", f"l{triangles}", tuple(joints))


def test_a_tree_thousands_of_levels_deep_is_laid_out_without_recursion():
    from mobility.report.plotting.graph import tree_layout

    root = decompose(ladder(3000)).root
    pos, edges, nodes = tree_layout(root)
    assert len(pos) == len(nodes) == len(edges) + 1 == 2 * 6001 - 1  # 6,001 leaves, a binary tree
    children: dict[int, list[int]] = {}
    for parent, child in edges:
        children.setdefault(parent, []).append(child)
    for parent, kids in children.items():  # each parent above the middle of its children, one level up
        xs = [pos[k][0] for k in kids]
        assert pos[parent] == (0.5 * (min(xs) + max(xs)), pos[kids[0]][1] + 1.0)
    leaves = sorted(x for key, (x, _) in pos.items() if key not in children)
    assert leaves == [float(i) for i in range(6001)]


def test_choosing_views_for_thousands_of_points_takes_bounded_memory():
    import tracemalloc

    rng = np.random.default_rng(5)
    joints = rng.normal(size=(20000, 3))
    answer = np.array([[0.0, 0, 0], [1, 0, 0], [0, 1, 0]])
    tracemalloc.start()
    views = choose_views(answer, np.array([[0.0, 0, 1]]), 6.0, count=2, context=joints)
    peak = tracemalloc.get_traced_memory()[1]
    tracemalloc.stop()
    assert len(views) == 2 and peak < 60 * 2**20  # every pair of 20,000 points in 252 views would be 800 GB
    # below the thinning bound the context counts point for point, as the points themselves do
    few = rng.normal(size=(40, 3))
    assert choose_views(answer, np.array([[0.0, 0, 1]]), 6.0, context=few) == choose_views(np.concatenate([few, answer]), np.array([[0.0, 0, 1]]), 6.0)


def test_a_large_mechanism_and_its_graph_are_drawn_with_collections():
    m = ladder(400)  # 801 joints, 402 links
    r = mobility.analyze(m)
    fig = plot_mechanism(m, r, views=1)
    gids = {a.get_gid() for a in fig.axes[0].get_children()}
    assert {"mobility:links:ground", "mobility:links:link:plates", "mobility:joints:R"} <= gids
    assert not any((g or "").startswith("mobility:link:") for g in gids)  # no artist per link
    graph = plot_graph(m, r)
    kinds = {a.get_gid() for a in graph.axes[1].collections}
    assert {"mobility:tree:joint", "mobility:tree:series", "mobility:tree:parallel"} <= kinds
    assert sum(len(a.get_offsets()) for a in graph.axes[1].collections if (a.get_gid() or "").startswith("mobility:tree:")) == 2 * 801 - 1
    assert not graph.axes[1].texts[1:]  # only the end effector's line: no box per node
    assert "names left out" in graph._suptitle.get_text()


DOLLARS = """name: "cost $_$ mech"
ground: "$g$"
end_effector: coupler
joints:
  - {name: A, type: R, links: ["$g$", crank], axis: [0, 0, 1], point: [0, 0, 0]}
  - {name: "$_$", type: R, links: [crank, coupler], axis: [0, 0, 1], point: [1, 2, 0]}
  - {name: C, type: R, links: [coupler, rocker], axis: [0, 0, 1], point: [4, 2.5, 0]}
  - {name: D, type: R, links: [rocker, "$g$"], axis: [0, 0, 1], point: [5, 0, 0]}
"""


@pytest.mark.parametrize("options", [["plot"], ["plot", "--graph"], ["plot", "--constraints"], ["sweep", "--vary", "A=0:60:4", "--plot"]])
def test_names_with_dollars_are_drawn_as_written(tmp_path, capsys, options):
    path = tmp_path / "dollars.yaml"
    path.write_text(DOLLARS)
    picture = tmp_path / "p.png"
    args = options[:1] + [str(path)] + options[1:] + ([str(picture)] if options[0] == "sweep" else ["-o", str(picture)])
    assert main(args) == 0, capsys.readouterr().err
    assert picture.stat().st_size > 10_000


def test_a_flat_curve_keeps_a_readable_log_scale():
    from mobility.report.sweep_plot import plot_sweep

    r = mobility.sweep(mobility.load(ROOT / "mechanisms" / "parallelogram.yaml"), ["O1=10:20:5"])
    bottom = plot_sweep(r).axes[1]
    low, high = bottom.get_ylim()
    assert high / low >= 4.0 and low < r.smallest_kept.min() and high > r.smallest_kept.max()
