"""The core: screw algebra, the model, the topology and the analysis.

Everything a feature builds on, nothing that knows of files or features.
Modules in data-flow order (each imports only those before it):
``tolerance``, ``transforms``, ``frozen``, ``linalg`` (the one tolerance
policy, rigid transforms, read-only arrays, the SVD); ``screws``,
``finite_screws``; ``model``; ``topology`` (the series/parallel tree);
``joint_screws`` (normalised joint twists); ``screw_systems``,
``loop_closure``, ``canonical``, ``kinematics`` (the two routes, readable
bases, finite motion); ``poses``; ``result``, ``analysis``.  Public names are
imported from the modules (``from mobility.core.analysis import analyze``);
the most used are also on :mod:`mobility`.
"""
