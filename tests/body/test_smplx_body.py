"""The optional SMPL-X loader, through a stand-in ``smplx`` module (SMPL-X's model files cannot
ship): joint mapping, weight folding, frame placement, and the message when smplx is missing."""

import sys
import types

import numpy as np
import pytest
import trimesh

from unsew.errors import InputError


class _Out:
    def __init__(self, v, j):
        import torch

        self.vertices = torch.as_tensor(v[None], dtype=torch.float32)
        self.joints = torch.as_tensor(j[None], dtype=torch.float32)


def _fake_smplx(tmp_path):
    import torch

    from unsew.body.body import default_body

    b = default_body()
    # a body with a separate small "eyeball" component, 55 joints and SMPL-X-like weights
    eye = trimesh.creation.icosphere(subdivisions=1, radius=0.01)
    v = np.concatenate([b.verts + [0.0, 0.3, 0.0], eye.vertices + [0.03, 1.85, 0.08]])
    f = np.concatenate([b.faces, eye.faces + len(b.verts)])
    from unsew.body.smplx_body import SMPLX_JOINTS

    J = np.zeros((55, 3))
    for name, (idx, _, _) in SMPLX_JOINTS.items():
        src = name if name in b.skeleton.names else "chest"
        J[idx] = b.skeleton.positions[b.skeleton.names.index(src)] + [0.0, 0.3, 0.0]
    W = np.zeros((len(v), 55))
    W[:, 30] = 1.0  # a left-hand finger joint: must fold onto left_wrist (index 20)

    class Model:
        faces = f
        lbs_weights = torch.as_tensor(W)

        def __call__(self, **kw):
            return _Out(v, J)

    mod = types.ModuleType("smplx")
    mod.create = lambda path, **kw: Model()
    return mod, b


def test_loader_with_stand_in(tmp_path, monkeypatch):
    mod, b = _fake_smplx(tmp_path)
    monkeypatch.setitem(sys.modules, "smplx", mod)
    from unsew.body.smplx_body import make_smplx_body

    body = make_smplx_body(tmp_path)
    assert len(body.verts) == len(b.verts)  # the eyeball component is dropped
    assert abs(body.verts[:, 1].min()) < 1e-6  # soles on the floor
    sk = body.skeleton
    assert np.allclose(sk.positions[sk.names.index("pelvis")][[0, 2]], 0.0, atol=1e-6)
    assert not sk.missing()
    col = sk.names.index("left_wrist")
    assert np.allclose(body.weights[:, col], 1.0)


def test_missing_smplx_is_one_line(monkeypatch, tmp_path):
    monkeypatch.setitem(sys.modules, "smplx", None)
    from unsew.body.smplx_body import make_smplx_body

    with pytest.raises(InputError, match="pip install unsew\\[smplx\\]"):
        make_smplx_body(tmp_path)
