"""Topics of the course beside the main pipeline: mass concentration (s. 2.2), gears
(s. 2.3.3), efficiency (s. 4.3).
"""

from __future__ import annotations

