"""The flexible engine's time-stepping kernel: the impacts' linear system
(:mod:`~batcert.engines.kernel.linear_system`), the coupling of the modes to the footprint
(:mod:`~batcert.engines.kernel.coupling`), the ETDRK4 scheme's constants
(:mod:`~batcert.engines.kernel.etdrk4`) and the march (:mod:`~batcert.engines.kernel.march`,
one step in :mod:`~batcert.engines.kernel.march_step`, the modal update in
:mod:`~batcert.engines.kernel.modal_update`). Only the engines use it; the physics it integrates
(the beam, the shell, the ball's law) lives in :mod:`batcert.physics`.
"""
