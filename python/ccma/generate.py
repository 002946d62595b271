"""ccma.generate: `ccma generate` from Python (docs/cli.md, `ccma generate`)."""
from . import _ccma
from ._tables import out_path
from .results import GenerateResult
from .viewer import _write_replacing


def generate(agents, kind="ccma", out=None):
    """`ccma generate`: a generated model, validated by loading it.

    agents: mobile bases (kind 'ccma'), legs ('stewart_gough', >= 6) or quadrupeds
    ('legged'), 3..1000; kind: 'ccma' (mobile bases with R-R-S legs, the family of
    6dof_six_agents), 'stewart_gough' (a UPS platform on the ground, actuated legs) or
    'legged' (quadrupeds each carrying an arm, the family of 6dof_three_legged); out: also
    write the model file there (replaced atomically, never through a planted link).
    Returns a ccma.GenerateResult: the command's JSON as attributes (to_dict()): model,
    agents, actuated_joints, bodies, state_size, controls, out; `new_model` is the
    ccma.Model, `text` its model file. Raises ValueError for what the command refuses (naming the flag)."""
    if isinstance(agents, bool) or not isinstance(agents, int):
        raise ValueError("generate: agents must be an integer (--agents)")
    model, text, document = _ccma._generate(str(kind), agents)
    out = out_path(out)
    if out is not None:
        _write_replacing(out, text.encode("utf-8"))
    document["out"] = out
    return GenerateResult(document, new_model=model, text=text)
