"""The mechanism model: the scene (bodies, joints, driver, loads), reading TOML, the
exceptions, and the bundled scenes.
"""

from __future__ import annotations

