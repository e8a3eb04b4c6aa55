"""Motion/force transmission indices of parallel mechanisms, from the screw systems of the analysis.

How well a pose transmits motion and force, in the measures the field
publishes (see :mod:`mobility.transmission.indices` for the definitions and
their sources):

* the **input transmission index** ``ITI`` of each input (Wang, Liu, Wang and
  Wang, 2010): how well the actuated joint's motion passes into its limb's
  transmission wrench; 0 where the limb is at a serial (input) singularity;
* the **output transmission index** ``OTI`` of each input: how well that
  wrench moves the end effector; 0 at an actuation (type II, output)
  singularity;
* the **local transmission index** ``LTI = min(ITI, OTI)`` over the inputs,
  the distance to an actuation singularity of either kind;
* the **constraint transmission index** ``CTI`` of each limb (the output
  constraint index of Liu and co-authors; the pressure angle of the
  constraint wrench of Brinker, Corves and Takeda): how well the limb's
  constraint wrench resists the motion it exists to stop; 0 at a constraint
  singularity, the distance to one.

Each index is a *power coefficient*: the reciprocal product of a wrench and a
twist divided by its largest value over the directions the wrench could take
at its point of application (the cosine of a pressure angle), so it is
dimensionless, between 0 and 1, and the same in any frame and any length unit.

:func:`transmission_indices` computes them on stacks of poses (the sweep's
arrays); :func:`mobility.check_transmission` at one pose of a mechanism.
"""

from .indices import (
    GOOD_TRANSMISSION,
    BatchTransmission,
    TransmissionCheck,
    power_coefficient,
    transmission_indices,
)

__all__ = ["GOOD_TRANSMISSION", "BatchTransmission", "TransmissionCheck", "power_coefficient", "transmission_indices"]
