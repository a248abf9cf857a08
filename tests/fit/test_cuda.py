"""Phase two on a GPU (``FitConfig.device``, ``unsew fit --device cuda``): phase one runs on the
CPU, :class:`~unsew.fit.optimize.PhaseTwo` moves what it computes with to the device once, and the
drapes' factorizations stay on the CPU. On a GPU: two iterations on "cuda" and on "cpu" from the
same start give the same losses, the result comes back as CPU data, a checkpoint written on the GPU
resumes on either device, and the CLI fit runs end to end. Without CUDA those are skipped; the test
that runs everywhere checks that phase two makes no tensor on the default device (what broke the
first GPU fit: index tensors left on the CPU).

On a GPU machine:  python -m pytest -q -rs tests/fit/test_cuda.py tests/sim/test_sim_device.py
"""

import json

import numpy as np
import pytest
import torch
from helpers import assert_close, no_default_device

from unsew.fit.config import load_config
from unsew.fit.scene import Scene

SMALL = {
    "drape.edge_length": 0.04,
    "optimizer.iterations": 2,
    "drape.steps": 8,
    "drape.sew_steps": 60,
    "drape.settle_steps": 20,
    "loss.target_points": 1500,
    "material.start_iteration": 1,
    "material.start": "cotton",
}
CUDA = pytest.mark.skipif(not torch.cuda.is_available(), reason="no CUDA device")


@pytest.fixture(scope="module")
def case_dir(tmp_path_factory):
    from unsew.fit.demo import make_truth_case

    return make_truth_case(tmp_path_factory.mktemp("case") / "tshirt", settings=load_config(**SMALL).drape)


@pytest.fixture(scope="module")
def phase_one(case_dir):
    """Phase one once, on the CPU (base dressed and graded in cotton): (MaterialChoice, Target,
    BodySDF, FitConfig)."""
    from unsew.body.case import load_case
    from unsew.body.sdf import BodySDF
    from unsew.fit.material import MaterialChoice
    from unsew.fit.start import base_pattern_for, start
    from unsew.fit.target import Target
    from unsew.sim.material import get_material

    case = load_case(case_dir)
    cfg = load_config(**SMALL)
    sdf, target = BodySDF.build(case.body), Target.of_case(case, seed=cfg.seed)
    s = start(base_pattern_for(case, cfg), Scene(case.body, target, sdf, cfg), get_material("cotton"))
    return MaterialChoice(s), target, sdf, cfg


def _phase_two(phase_one, device):
    from unsew.fit.optimize import PhaseTwo

    choice, target, sdf, cfg = phase_one
    return PhaseTwo(choice, target, sdf, cfg.replace(device=device))


def test_phase_two_makes_nothing_on_the_default_device(phase_one):
    """Every tensor phase two creates while it drapes, back-propagates, steps (the material a
    variable from the second iteration), returns its result and resumes takes the device of its
    inputs (checked on the CPU: :func:`helpers.no_default_device`)."""
    two, other = _phase_two(phase_one, "cpu"), _phase_two(phase_one, "cpu")
    with no_default_device():
        two.run()
        _, uv, x, _ = two.best_fit()
        two.gamma_last()
        other.load_state_dict(two.state_dict())
    assert len(two.history["total"]) == 2 and isinstance(uv, np.ndarray) and isinstance(x, np.ndarray)


@CUDA
def test_phase_two_on_cuda_matches_cpu(phase_one, tmp_path):  # pragma: no cover - no GPU on the dev machines
    """Two iterations on the GPU and on the CPU from the same start: the same loss terms (float64;
    the sums on the GPU run in another order), and best_fit()/gamma_last() hand back CPU data. A
    checkpoint written on the GPU is read onto the CPU and resumes on either device alike."""
    from unsew.fit.checkpoint import load_checkpoint, save_checkpoint
    from unsew.fit.optimize import LOSS_TERMS

    cpu, gpu = _phase_two(phase_one, "cpu"), _phase_two(phase_one, "cuda")
    cpu.run()
    gpu.run()
    assert (
        gpu.model.device.type == "cuda"
        and gpu.params.L_u.device.type == "cuda"
        and gpu.T.device.type == "cuda"
    )
    assert gpu.K.device.type == "cuda" and gpu.best.x.device.type == "cuda"
    for k in LOSS_TERMS:
        assert_close(gpu.history[k], cpu.history[k], rtol=1e-6, atol=1e-15, what=f"{k} ")
    assert cpu.history["total"][1] != cpu.history["total"][0]  # it moved
    pattern, uv, x, material = gpu.best_fit()
    _, uv_c, x_c, material_c = cpu.best_fit()
    assert isinstance(uv, np.ndarray) and isinstance(x, np.ndarray)
    assert_close(uv, uv_c, atol=1e-9, rtol=0, what="uv ")
    assert_close(x, x_c, atol=1e-7, rtol=0, what="x ")
    assert set(pattern.panels) == set(cpu.best_fit()[0].panels)
    assert material.h00 == pytest.approx(material_c.h00, rel=1e-6)
    assert all(type(v) is float for v in gpu.gamma_last())
    path = tmp_path / "checkpoint.pt"
    save_checkpoint(path, phase_one[0], gpu.state_dict())
    _, state = load_checkpoint(path)
    assert state["K"].device.type == "cpu" and state["best"]["x"].device.type == "cpu"
    resumed = {}
    for device in ("cuda", "cpu"):
        two = _phase_two(phase_one, device)
        two.load_state_dict(state)
        assert two.best.x.device.type == device and two.K.device.type == device
        two.step()
        resumed[device] = two.history["total"]
    assert len(resumed["cuda"]) == 3
    assert_close(resumed["cuda"], resumed["cpu"], rtol=1e-6, atol=0)


@CUDA
def test_fit_cli_on_cuda(case_dir, tmp_path, capsys):  # pragma: no cover - no GPU on the dev machines
    """``unsew fit CASE --device cuda`` in small mode: exit 0, the result folder with metrics.json
    (the re-dress check and the outputs took phase two's result as CPU data), the device recorded."""
    import yaml

    from unsew.cli import main

    cfg = tmp_path / "small.yaml"
    cfg.write_text(yaml.safe_dump({**SMALL, "checks.mesh_spread": 0.0}))
    out = tmp_path / "result"
    code = main(
        ["fit", str(case_dir), "--out", str(out), "--config", str(cfg), "--device", "cuda", "--no-progress"]
    )
    err = capsys.readouterr().err
    assert code == 0, err
    metrics = json.loads((out / "metrics.json").read_text())
    assert metrics["iterations"] == 2 and len(metrics["loss_history"]["total"]) == 2
    assert np.isfinite(metrics["surface"]["chamfer_mm"]) and "redress" in metrics
    assert yaml.safe_load((out / "config.yaml").read_text())["config"]["device"] == "cuda"
