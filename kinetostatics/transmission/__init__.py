"""How a mechanism transmits power: gears (tooth force, ratio, the equilibrating moment
of a pair and of a train, seed 002 s. 2.3.3) and efficiency (mean and instantaneous,
machines in series, parallel and mixed, s. 4.3)."""
