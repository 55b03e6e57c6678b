"""The balancing model: reading a balancing scene (:func:`~.scene.load_scene`), its units
(:mod:`.units`, :mod:`.scene_units`), the field sections' specs (:mod:`.field_scene`),
the readings' noise model (:mod:`.noise`) and the checks for unit slips (:mod:`.slips`).
"""

from __future__ import annotations
