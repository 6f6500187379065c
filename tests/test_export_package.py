"""Every name in fastrest.export.__all__ is an attribute of the package after a plain import."""
import subprocess
import sys


def test_submodules_reachable_from_a_fresh_import():
    code = ("import fastrest.export as e, types\n"
            "mods = [getattr(e, n) for n in e.__all__]\n"
            "assert all(isinstance(m, types.ModuleType) for m in mods)\n"
            "assert [m.__name__ for m in mods] == ['fastrest.export.' + n for n in e.__all__]\n"
            "assert set(e.__all__) <= set(dir(e))\n"
            "try:\n    e.no_such_thing\nexcept AttributeError as exc:\n    assert 'no_such_thing' in str(exc)\n"
            "else:\n    raise SystemExit('no AttributeError')\n")
    subprocess.run([sys.executable, "-c", code], check=True, timeout=300)
