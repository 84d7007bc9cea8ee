"""Shafts and bearings that carry the gears: their layout and two models of one interface.

- :mod:`.layout` - a shaft as the gearbox file describes it (segments, the gear's seat,
  bearings, where the torque is held, material), checked where it enters.
- :mod:`.model` - what every shaft model gives (:class:`~.model.ShaftModel`): the solution
  under loads at the seat (deflection line, bearing reactions), the flexibility between
  points of the seat, the stiffness condensed to the seat's centre.
- :mod:`.beam` - the ``"beam"`` model (:class:`~.beam.BeamShaft`): Timoshenko beam elements
  (:mod:`.timoshenko`) on nodes at every key point (:mod:`.nodes`), the rigid seat and the
  rigid supports eliminated exactly (:mod:`.constraints`).
- :mod:`.fe3d` - ``model = "fe3d"``: the shaft meshed in Gmsh, solved in scikit-fem and
  condensed to the seat, the bearings and the torque point (:class:`~.fe3d.Fe3dShaft`);
  :mod:`.fe3d_plan` turns a layout into its pieces, reference nodes and bands.
"""
