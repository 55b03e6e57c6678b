"""The mechanism model: the scene (bodies, joints, driver, loads), reading TOML
(:func:`~.scene.load_scene`), the exceptions, and the bundled scenes.
"""

from __future__ import annotations

