"""Motion/force transmission indices of parallel mechanisms, from the screw systems of the analysis.

The input, output, local and constraint transmission indices ``ITI``,
``OTI``, ``LTI`` and ``CTI``: dimensionless power coefficients between 0 and 1,
0 at a singularity of their kind (definitions and sources in
:mod:`mobility.transmission.indices`).  :func:`transmission_indices` computes
them on stacks of poses (the sweep's arrays); :func:`mobility.check_transmission`
at one pose of a mechanism.
"""

from .indices import GOOD_TRANSMISSION, BatchTransmission, TransmissionCheck, power_coefficient, transmission_indices

__all__ = ["GOOD_TRANSMISSION", "BatchTransmission", "TransmissionCheck", "power_coefficient", "transmission_indices"]
