import os
import sys

import pytest

sys.path.insert(0, os.path.dirname(__file__))
import pynari as anari  # noqa: E402


@pytest.fixture(scope='module')
def device():
    return anari.newDevice('default')
