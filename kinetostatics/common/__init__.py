"""The lowest floor: small pieces every other package may use, importing nothing of the
project (its modules are imported one by one: this ``__init__`` loads none of them).

* :mod:`~kinetostatics.common.cli`: what ``python -m kinetostatics`` and ``python -m
  balance`` share (the argument parser whose every mistake is one line, the ``--dpi``
  option's type, one-line messages and warnings);
* :mod:`~kinetostatics.common.jsontext`: numpy values as plain JSON;
* :mod:`~kinetostatics.common.lazy`: a package's public names imported on first use
  (PEP 562).
"""
