# pytest fixtures for the Python module: the zsweep binary (the CLI the
# module must match bit for bit) and a scratch directory per test.
import os
import subprocess

import numpy as np
import OpenImageIO as oiio
import pytest

ZSWEEP = os.environ.get("ZSWEEP", "")


@pytest.fixture
def cli(tmp_path):
    """cli(scene_or_input, *args) -> (float image array (H, W, C), channel names) of `zsweep render`."""
    if not ZSWEEP:
        pytest.skip("ZSWEEP (the zsweep binary) is not set")

    def run(inp, *args):
        out = str(tmp_path / "cli.exr")
        subprocess.run([ZSWEEP, "render", str(inp), "-o", out, *map(str, args)], check=True,
                       stdout=subprocess.DEVNULL)
        f = oiio.ImageInput.open(out)
        spec = f.spec()
        img = f.read_image(format="float")
        f.close()
        return np.asarray(img, dtype=np.float32), list(spec.channelnames)

    return run
