"""ccma.generate is `ccma generate`: the same file, the same JSON."""
import pytest

import ccma
from conftest import run_tool


@pytest.mark.parametrize("kind,agents", [("ccma", 6), ("stewart_gough", 6), ("legged", 4), ("ccma", 3)])
def test_generate_equals_the_command(tmp_path, kind, agents):
    cli_out = tmp_path / "cli.yaml"
    cli = run_tool("generate", "--kind=" + kind, "--agents=" + str(agents), "--out=" + str(cli_out))
    r = ccma.generate(agents, kind=kind, out=tmp_path / "py.yaml")
    assert (tmp_path / "py.yaml").read_text() == cli_out.read_text() == r.text
    expected = dict(cli, out=str(tmp_path / "py.yaml"))
    assert r.to_dict() == expected
    assert r.new_model.num_controls == cli["controls"]
    # Without out=, nothing is written and out is None.
    assert ccma.generate(agents, kind=kind).out is None


def test_generate_checks_what_the_command_checks():
    with pytest.raises(ValueError, match="--agents must be an integer >= 3"):
        ccma.generate(2)
    with pytest.raises(ValueError, match="--agents must be at most 1000"):
        ccma.generate(1001)
    with pytest.raises(ValueError, match="--kind=stewart_gough needs --agents >= 6"):
        ccma.generate(5, kind="stewart_gough")
    with pytest.raises(ValueError, match="--kind must be ccma, stewart_gough or legged"):
        ccma.generate(6, kind="delta")
    with pytest.raises(ValueError, match="agents must be an integer"):
        ccma.generate(6.5)
