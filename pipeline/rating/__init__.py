"""Load capacity rating of ISO 6336: the safety factors S_H and S_F of every gear of a mesh.

- :mod:`.pitting` - ISO 6336-2 method B: the contact stress chain (Z_H, Z_E, Z_eps,
  Z_beta, Z_B / Z_D, sigma_H0, sigma_H), the permissible contact stress (Z_NT, Z_L, Z_v,
  Z_R, Z_W, Z_X) and S_H of each gear.
- :mod:`.accuracy` - ISO 1328-1:1995 tolerances of an accuracy grade (f_pt, f_pb, F_p,
  profile and helix deviations), the inputs of ISO 6336-1's load factors.
- :mod:`.dynamic` - ISO 6336-1 method B dynamic factor K_v in every range of the resonance
  ratio (the reduced mass of a pair or a planetary mesh, n_E1, running-in allowances, B_p,
  B_f, B_k).
- :mod:`.pair_rating` - :func:`rate_pair`: every factor of a mesh's rating in one record
  (a pair, or a planetary set's sun-planet or planet-ring mesh).
- :mod:`.options` - the ``[rating]`` table's inputs (defaults, K_gamma by planet count).
- :mod:`.transverse` - ISO 6336-1 method B transverse load factors K_Halpha and K_Falpha.
- :mod:`.face_load` - ISO 6336-1 method C face load factor K_Hbeta (and K_Fbeta from it).
- :mod:`.bending` - ISO 6336-3 method B: sigma_F from the nominal root stress of
  :mod:`pipeline.contact.iso_root_stress` and the load factors (K_Fbeta from K_Hbeta),
  the permissible root stress (Y_ST, Y_NT, Y_deltarelT, Y_RrelT, Y_X) and S_F.
- :mod:`.materials` - ISO 6336-5:2016 Table 1: sigma_Hlim, sigma_Flim and a material's classes.
- :mod:`.life` - the life factor lines, the limited-life range of the influence factors
  (log-log to their static values below the knee) and the S-N line of a gear
  (:class:`~.life.StrengthCurve`) with its inverse.
- :mod:`.spectrum` - ISO 6336-6 load spectra: the Palmgren-Miner damage of each gear and
  failure mode and the spectrum's safety factor, from the stresses the caller gives per bin;
  :mod:`.pair_spectrum` rates a mesh's bins with :func:`rate_pair`.
- :mod:`.local_safety` - beyond the standard: the local pitting safety over each flank from
  the loaded contact's Hertz pressure, and the FE root stress along the face.

The run's step (:mod:`pipeline.run.rating`) takes the ``[rating]`` table
(:mod:`pipeline.config.rating`) and what the run knows (the loaded contact's K_Hbeta, the
planets' load sharing, the FE root stress) and rates every mesh; internal gears are rated
in bending with the root section their pinion-type cutter generates
(:mod:`pipeline.contact.iso_root_stress`).

Checked against ISO/TR 6336-30's example 1 (pitting, as transcribed) and KISSsoft's reports
of the NREL 5 MW gearbox (pitting of the parallel stage and of both meshes of a planetary
stage, bending of the parallel stage and of a sun and a planet, K_v and K_Halpha of three
meshes, the tolerances of all eight gears; a ring's bending from KISSsoft's printed root
section; a gearbox file of the parallel stage through ``gearpipe run``) and ISO 6336-6's
Annex C spectrum (Table C.2). Not built: the slip layer of St, GG, GGG (ferr.), NT and NV
roots (rated in pitting only), the rim factor Y_B of thin rims.
"""
