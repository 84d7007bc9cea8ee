"""Options of the analytical mesh stiffness stage."""

from __future__ import annotations

from dataclasses import dataclass

from pipeline.stiffness.mesh import FrictionModel
from pipeline.validation import check_choice, check_int_range, check_range


@dataclass(frozen=True)
class StiffnessOptions:
    """Options of the analytical (potential-energy) mesh stiffness.

    Attributes
    ----------
    friction : constant friction coefficient mu (-) in [0, 0.5], or "ehl" for the EHL
        regression of Xu et al. (2007).
    positions : samples per mesh cycle, in [8, 100000].
    slices : slices over the face width of helical gears, in [1, 2000].
    foundation_correction : factor on the fillet-foundation stiffness when several pairs
        are in contact, in [0.5, 2] (1 disables).
    roughness : RMS roughness of the flanks, m (EHL friction), in [0, 100] um.
    viscosity : dynamic viscosity of the oil at inlet temperature, Pa s (EHL friction).
    """

    friction: float | str = 0.0
    positions: int = 360
    slices: int = 100
    foundation_correction: float = 1.0
    roughness: float = 0.5e-6
    viscosity: float = 0.02

    def __post_init__(self) -> None:
        if isinstance(self.friction, str):
            check_choice("stiffness.friction", self.friction, ("ehl",))
        else:
            check_range("stiffness.friction", self.friction, 0.0, 0.5)
        check_int_range("stiffness.positions", self.positions, 8, 100_000)
        check_int_range("stiffness.slices", self.slices, 1, 2_000)
        check_range("stiffness.foundation_correction", self.foundation_correction, 0.5, 2.0)
        check_range("stiffness.roughness", self.roughness, 0.0, 1e-4, unit="m")
        check_range("stiffness.viscosity", self.viscosity, 1e-5, 10.0, unit="Pa s")

    @property
    def friction_model(self) -> FrictionModel:
        """The friction model these options ask for."""
        if isinstance(self.friction, str):
            return FrictionModel(kind="ehl", roughness=self.roughness, viscosity=self.viscosity)
        return FrictionModel(mu=float(self.friction))
