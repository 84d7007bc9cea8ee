"""Load capacity rating of ISO 6336 (in progress, issue 27).

- :mod:`.pitting` - ISO 6336-2 method B: the contact stress chain (Z_H, Z_E, Z_eps,
  Z_beta, Z_B / Z_D, sigma_H0, sigma_H), the permissible contact stress (Z_NT, Z_L, Z_v,
  Z_R, Z_W, Z_X) and S_H of each gear.
"""
