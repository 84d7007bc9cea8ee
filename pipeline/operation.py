"""The operating point of a gear mesh or gearbox: load and speed of the driving member."""

from __future__ import annotations

from dataclasses import dataclass

from pipeline.validation import check_choice, check_range

DRIVERS = ("pinion", "gear")


@dataclass(frozen=True)
class OperatingPoint:
    """Load and speed of the driving gear.

    Attributes
    ----------
    torque : N m on the driving gear, in (0, 1e8].
    speed : rad/s of the driving gear, in (0, 1e5].
    driver : "pinion" or "gear".
    """

    torque: float = 100.0
    speed: float = 100.0
    driver: str = "pinion"

    def __post_init__(self) -> None:
        check_range("operation.torque", self.torque, 0.0, 1e8, lo_open=True, unit="N m")
        check_range("operation.speed", self.speed, 0.0, 1e5, lo_open=True, unit="rad/s")
        check_choice("operation.driver", self.driver, DRIVERS)
