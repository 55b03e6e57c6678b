"""The mechanism model: the scene (bodies, joints, driver, loads), reading TOML (one
scene: :func:`~.scene.load_scene`; many dicts of one form at once:
:func:`~.batch.load_scenes`), the exceptions, and the bundled scenes.
"""

from __future__ import annotations

