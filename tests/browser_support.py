"""What the browser tests share: finding the system Chromium that Playwright drives.

Playwright's own browser download is not available here, so the tests use the system browser
(`.ci/install-browser`, run by `.ci/run`, installs Debian's `chromium`) and skip, saying how to
install it, where there is none.
"""

from __future__ import annotations

import shutil

import pytest


def chromium_executable(purpose: str) -> str:
    """The path of the system Chromium, or a pytest skip that names what it was needed for."""
    for name in ("chromium", "chromium-browser", "google-chrome"):
        found = shutil.which(name)
        if found:
            return found
    pytest.skip(f"no Chromium on this machine: install Debian's `chromium` (apt-get install chromium; .ci/run "
                f"does) to {purpose}")
