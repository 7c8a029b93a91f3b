# SPDX-License-Identifier: Apache-2.0
"""A closed-loop servo testbed: the servomechanism of Bascetta, "Motion control: advanced control
techniques" (Politecnico di Milano lecture notes) under the controllers the notes compare, with
the library's filters on its reference.

* :mod:`.plant`: the elastic two-mass model (the notes' parameter table), the rigid model, the
  normalised servo of the notch example, and their exact ZOH discretisation;
* :mod:`.design`: the design rules (P/PI gains, the TDO, pole placement with integral action,
  LQ and Kalman gains, the reference model behind the feed-forward compensators);
* :mod:`.controllers`: each controller as one sampled step;
* :mod:`.loop`: :class:`Drive`, the closed loop (poles, frequency responses, simulation).

``docs/servo.md`` explains the designs and tabulates the results.

Example::

    from smoothshaper import servo
    drive = servo.Drive(servo.elastic_servo(), servo.PID(wcv=107.0, Ti=0.093, wcp=10.7), Ts=5e-4)
    out = drive.simulate(reference)          # load reference [rad] per sample
    out["w_l"]                               # load velocity [rad/s]
"""
from .plant import (NOTES, DiscretePlant, ServoPlant, discretize, elastic_servo, locked_frequency,
                    rigid_servo, servo_from_modes)
from .controllers import LQG, PID, TDO, PolePlacement
from .loop import INPUTS, OUTPUTS, Drive
from . import design, presets

__all__ = ["NOTES", "ServoPlant", "DiscretePlant", "elastic_servo", "rigid_servo",
           "servo_from_modes", "discretize", "locked_frequency", "PID", "TDO", "PolePlacement",
           "LQG", "Drive", "INPUTS", "OUTPUTS", "design", "presets"]
