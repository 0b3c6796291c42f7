"""Options objects: the CLI's defaults, validation with the CLI's messages."""
import pytest

import mocapsolve


def test_defaults_validate():
    mocapsolve.SolverSettings().validate()
    mocapsolve.RepairSettings().validate()
    mocapsolve.FalloffSettings().validate(100)
    mocapsolve.RetargetSettings().validate()
    mocapsolve.CorruptionSettings().validate()


@pytest.mark.parametrize("make,field,value,message", [
    (mocapsolve.SolverSettings, "dls_damping", "none", "--dls_damping: unknown 'none'"),
    (mocapsolve.RepairSettings, "reference", "x", "--reference: unknown 'x'"),
    (mocapsolve.RetargetSettings, "iterations", 0, "--iterations: must be in [1, 1000]"),
    (mocapsolve.CorruptionSettings, "gap_min", 0, "--gap_min/--gap_max"),
])
def test_bad_values_raise_the_cli_message(make, field, value, message):
    settings = make()
    setattr(settings, field, value)
    with pytest.raises(ValueError) as error:
        settings.validate()
    assert message in str(error.value)


def test_falloff_region_is_checked_against_the_clip():
    settings = mocapsolve.FalloffSettings()
    settings.region = "10:500"
    with pytest.raises(ValueError, match="--region"):
        settings.validate(100)
    settings.validate(600)
