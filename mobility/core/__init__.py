"""The core: screw algebra, the model, the topology and the analysis.

Everything a feature builds on, and nothing that knows of files or features.
Modules, in data-flow order (a module imports only those before it):

``tolerance``, ``transforms``, ``frozen``, ``linalg``
    the one tolerance policy; rigid transforms; read-only arrays for frozen
    results (also after pickling); the SVD.
``screws``, ``finite_screws``
    instantaneous screws (twists ``[w; v]``, wrenches ``[f; m]``, the adjoint)
    and finite screws.
``model``
    :class:`~mobility.core.model.Mechanism`, ``Joint``, ``Frame``: frozen descriptions.
``topology``
    the joint graph and its series/parallel tree.
``joint_screws``
    a model's joint twists in normalised coordinates.
``screw_systems``, ``loop_closure``, ``canonical``, ``kinematics``
    the series/parallel route, the independent loop-closure route, readable
    bases, and finite motion (joint displacements, loops re-closed by Newton).
``poses``
    assembled poses away from the given one, by a seeded random walk.
``result``, ``analysis``
    the frozen :class:`~mobility.core.result.Result` (with the screw system
    found at every node of the tree, ``node_systems``) and
    :func:`~mobility.core.analysis.analyze`.

The public names are imported from the modules themselves
(``from mobility.core.analysis import analyze``); the most used ones are also
on the package :mod:`mobility`.
"""
