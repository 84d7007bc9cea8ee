"""Gearbox models built from bodies and couplings: spur pair, planetary sets, split torque."""
