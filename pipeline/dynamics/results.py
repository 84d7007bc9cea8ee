"""Result objects of the dynamic solvers (named fields, SI units, shapes documented)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

MODE_KINDS = ("", "rigid", "rotational", "translational", "planet", "mixed", "axial")
"""Mode kinds in the order of their codes in ``modes.csv``."""

MOTIONS = ("in-plane", "rotation", "axial")
"""Groups of coordinates whose kinetic-energy shares a mode reports: in-plane translations
(``x``, ``y``), rotations about the gear axes (``theta``) and axial translations (``z``)."""

DTE_SPECTRUM_COLUMNS = ("mesh order [-]", "DTE amplitude [m]")
"""Column names of ``dte_spectrum.csv``; the README's figure table lists the same names."""

_MOTION_DOFS = {"in-plane": ("x", "y"), "rotation": ("theta",), "axial": ("z",)}


@dataclass(frozen=True)
class Response:
    """A time history: transient (time integration) or one steady period.

    Attributes
    ----------
    time : shape (N,), s.
    q : shape (N, n_full), displacements of every named coordinate (m, rad), measured
        from the rigid-body motion when the system has one.
    qd : shape (N, n_full), velocities (m/s, rad/s).
    dte : shape (n_mesh, N), dynamic transmission error delta = v . q along each
        line of action, m.
    mesh_force : shape (n_mesh, N), dynamic mesh force k (delta - e) + c (delta' - e'), N.
    elastic_force : shape (n_mesh, N), its elastic part k (delta - e), N, or ``None``
        (then taken equal to ``mesh_force``). The dynamic factor is read from it
        (:meth:`dynamic_factor`).
    dof_names, mesh_names : labels of the columns of ``q`` and rows of ``dte``.
    period : system period T, s.
    steady_from : index of the first sample judged periodic (time integration), or 0.
    method : "propagator", "floquet" or "harmonic-balance".
    end_state : shape (2 n,), final state [q; q'] in the solver's independent
        coordinates (to continue a sweep from it), or ``None``.
    """

    time: np.ndarray
    q: np.ndarray
    qd: np.ndarray
    dte: np.ndarray
    mesh_force: np.ndarray
    dof_names: tuple[str, ...]
    mesh_names: tuple[str, ...]
    period: float
    steady_from: int = 0
    method: str = ""
    end_state: np.ndarray | None = None
    elastic_force: np.ndarray | None = None

    def mesh(self, name: str) -> int:
        """Row of a mesh in ``dte`` / ``mesh_force``."""
        return self.mesh_names.index(name)

    def coordinate(self, name: str) -> np.ndarray:
        """Time history (N,) of one named coordinate ``"body.dof"``."""
        return self.q[:, self.dof_names.index(name)]

    def steady_slice(self) -> slice:
        """Samples of whole steady periods: from ``steady_from`` to the end, without the
        last sample (it repeats the first one of the period), so means are exact."""
        end = self.time.size - 1 if self.time.size - self.steady_from > 1 else self.time.size
        return slice(self.steady_from, end)

    def rms_mesh_force(self) -> np.ndarray:
        """RMS of each mesh force over the steady part, shape (n_mesh,), N."""
        f = self.mesh_force[:, self.steady_slice()]
        return np.sqrt(np.mean(f**2, axis=1))

    def mean_mesh_force(self) -> np.ndarray:
        """Mean of each mesh force over the steady part, shape (n_mesh,), N."""
        return self.mesh_force[:, self.steady_slice()].mean(axis=1)

    def elastic_mesh_force(self) -> np.ndarray:
        """Elastic mesh force k (delta - e), shape (n_mesh, N), N (``mesh_force`` when the
        solver gives no separate elastic part, e.g. the quasi-static one)."""
        return self.mesh_force if self.elastic_force is None else self.elastic_force

    def dynamic_factor(self) -> np.ndarray:
        """Dynamic factor of each mesh over the steady part, shape (n_mesh,), -.

        ``K = max_t k(t) (delta(t) - e(t)) / mean_t F(t)``: the largest *elastic* mesh
        force over the mean mesh force. The damping force c (delta' - e') is left out of
        the maximum because the static transmission error e jumps where a tooth pair
        enters; e' is then a pulse one excitation sample wide whose height grows with the
        sampling of the contact cycle and the harmonics kept, so a maximum that includes it
        measures the sampling, not the gears. The elastic force needs only k, e and the
        DTE at each instant, which converge with the harmonics and the contact positions
        (the demo pair: 0.01 % from 40 to 160 harmonics, 0.2 % from 90 to 720 positions,
        where the maximum of the whole force moves up to 4 %). The mean is that of the whole
        force (equal to the elastic mean, the damping force averaging to zero over a
        steady period). Equals max / mean of ``mesh_force`` without mesh damping.
        """
        s = self.steady_slice()
        return self.elastic_mesh_force()[:, s].max(axis=1) / self.mesh_force[:, s].mean(axis=1)

    def peak_to_peak_dte(self) -> np.ndarray:
        """Peak-to-peak DTE over the steady part, shape (n_mesh,), m."""
        d = self.dte[:, self.steady_from :]
        return d.max(axis=1) - d.min(axis=1)

    def summary(self) -> dict:
        """Per mesh: RMS and mean force (N), DTE peak-to-peak and mean (m); the period (s)."""
        rms, mean, ptp = self.rms_mesh_force(), self.mean_mesh_force(), self.peak_to_peak_dte()
        return {
            "method": self.method,
            "period_s": self.period,
            "meshes": {m: {"rms_force_N": float(rms[i]), "mean_force_N": float(mean[i]),
                           "dte_peak_to_peak_m": float(ptp[i]),
                           "dte_mean_m": float(self.dte[i, self.steady_slice()].mean())}
                       for i, m in enumerate(self.mesh_names)},
        }

    def columns(self) -> dict[str, np.ndarray]:
        """Time history columns: time (s), then DTE (m), total force k (delta - e) +
        c (delta' - e') and elastic force k (delta - e) (N) of every mesh."""
        cols = {"time [s]": self.time}
        for i, m in enumerate(self.mesh_names):
            cols[f"dte {m} [m]"] = self.dte[i]
            cols[f"force {m} [N]"] = self.mesh_force[i]
            cols[f"elastic force {m} [N]"] = self.elastic_mesh_force()[i]
        return cols
    def dte_spectrum(self, mesh: int = 0) -> tuple[np.ndarray, np.ndarray]:
        """Single-sided spectrum of the steady DTE of mesh row ``mesh``: (frequency,
        shape (K,), Hz; amplitude, shape (K,), m). Row 0 (0 Hz) is the signed time mean
        of the DTE over the steady samples, rows k >= 1 the amplitude of order k."""
        d = self.dte[mesh, self.steady_slice()]
        dt = self.time[1] - self.time[0]
        a = np.abs(np.fft.rfft(d - d.mean())) / d.size
        a[1:] *= 2.0
        a[0] = d.mean()
        return np.fft.rfftfreq(d.size, dt), a

    def dte_spectrum_columns(self, mesh: int = 0) -> dict[str, np.ndarray]:
        """:meth:`dte_spectrum` as CSV columns: frequency in multiples of 1/T (the mesh
        order, as drawn in ``dte_spectrum.png``), -, and amplitude, m (order 0: the mean)."""
        f, a = self.dte_spectrum(mesh)
        return dict(zip(DTE_SPECTRUM_COLUMNS, (f * self.period, a), strict=True))


@dataclass(frozen=True)
class HarmonicResponse:
    """Steady periodic response from the harmonic balance.

    Attributes
    ----------
    response : one period sampled uniformly (see :class:`Response`).
    orders : shape (H+1,), harmonic orders 0..H of the fundamental 1/T.
    dte_amplitude : shape (n_mesh, H+1), single-sided amplitude of each DTE harmonic, m
        (order 0 is the mean).
    dte_contribution : shape (n_mesh, H), share of each order 1..H in the sum of the
        alternating amplitudes (Jin et al. 2018 "contribution proportion"), -.
    coefficients : shape (2H+1, n_full), complex Q_h of the full coordinates, h = -H..H.
    dte_coefficients : shape (2H+1, n_mesh), complex DTE coefficients D_h (m), h = -H..H:
        ``dte(t) = sum_h D_h exp(i 2 pi h t / T)``.
    """

    response: Response
    orders: np.ndarray
    dte_amplitude: np.ndarray
    dte_contribution: np.ndarray
    coefficients: np.ndarray
    dte_coefficients: np.ndarray | None = None


@dataclass(frozen=True)
class ModalResult:
    """Natural frequencies and modes.

    Attributes
    ----------
    frequencies : shape (m,), Hz, ascending (rigid-body modes at 0).
    shapes : shape (n_full, m), mass-normalised mode shapes of the named coordinates.
    dof_names : labels of the rows of ``shapes``.
    kinds : shape (m,) labels ("rigid", "rotational", "translational", "planet",
        "mixed", "axial", or "" when not classified; rule in :mod:`pipeline.dynamics.modal`).
    multiplicity : shape (m,), number of modes sharing the frequency (rel. tol 1e-6).
    weights : shape (n_full,), sqrt of the mass (or polar moment of inertia) of each named
        coordinate's own body (kg^0.5 or (kg m^2)^0.5); ``weights * shape`` is the
        kinetic-energy amplitude (its squares sum to 1 over the coordinates of a mode),
        which puts rotations and translations on one scale.
    """

    frequencies: np.ndarray
    shapes: np.ndarray
    dof_names: tuple[str, ...]
    kinds: tuple[str, ...]
    multiplicity: np.ndarray
    weights: np.ndarray | None = None

    def energy_shares(self) -> dict[str, np.ndarray]:
        """Share (-) of each mode's kinetic energy in each group of :data:`MOTIONS`.

        Returns
        -------
        ``{"in-plane": (m,), "rotation": (m,), "axial": (m,)}``: the sums of
        ``(weights * |shape|)**2`` over the coordinates ending in ``.x``/``.y``,
        ``.theta`` and ``.z``, divided by their total; the three add up to 1 for every
        mode. A model without ``z`` coordinates has axial shares 0.
        """
        if self.weights is None:
            raise ValueError("energy shares need the coordinate masses (ModalResult.weights)")
        e = np.abs(np.asarray(self.weights)[:, None] * self.shapes) ** 2
        total = e.sum(axis=0)
        total = np.where(total > 0.0, total, 1.0)
        dof = np.array([n.rsplit(".", 1)[-1] for n in self.dof_names])
        return {g: e[np.isin(dof, _MOTION_DOFS[g])].sum(axis=0) / total for g in MOTIONS}

    @property
    def rigid_body_modes(self) -> int:
        """Number of rigid-body modes (0 Hz)."""
        return int(np.count_nonzero(np.asarray(self.frequencies) == 0.0))

    def counts(self) -> str:
        """"56 coordinates, 29 independent DOF (1 rigid-body mode)": the named coordinates
        against the modes left once the ties between them (equal halves, a fixed member)
        are applied; one mode per independent DOF."""
        n, m, r = len(self.dof_names), self.frequencies.size, self.rigid_body_modes
        return (f"{n} coordinates, {m} independent DOF ({r} rigid-body "
                f"mode{'' if r == 1 else 's'})")

    def summary(self) -> dict:
        """Frequencies (Hz) of every mode (rigid-body modes at 0, kind "rigid"), mode kinds,
        multiplicities, kinetic-energy shares (-) of in-plane translation, rotation and axial
        translation; the number of named coordinates, of independent DOF (= modes) and of
        rigid-body modes."""
        out = {"frequencies_Hz": self.frequencies, "kinds": list(self.kinds),
               "multiplicity": self.multiplicity, "coordinates": len(self.dof_names),
               "independent_dofs": int(self.frequencies.size),
               "rigid_body_modes": self.rigid_body_modes}
        if self.weights is not None:
            out["energy_shares"] = self.energy_shares()
        return out

    def columns(self) -> dict[str, np.ndarray]:
        """One row per mode: frequency (Hz), multiplicity, kind code and the kinetic-energy
        shares (-) the kind is read from (:meth:`energy_shares`)."""
        codes = np.array([MODE_KINDS.index(k) if k in MODE_KINDS else 5 for k in self.kinds])
        cols = {"frequency [Hz]": self.frequencies, "multiplicity [-]": self.multiplicity,
                "kind [0 none,1 rigid,2 rot,3 trans,4 planet,5 mixed,6 axial]": codes}
        if self.weights is not None:
            names = {"in-plane": "in-plane translation", "rotation": "rotation",
                     "axial": "axial translation"}
            for g, v in self.energy_shares().items():
                cols[f"{names[g]} energy share [-]"] = v
        return cols

    def real_shapes(self) -> np.ndarray:
        """Mode shapes as real vectors, shape (n_full, m), same units as ``shapes``.

        Undamped non-gyroscopic modes are real already. A gyroscopic (complex) mode is
        turned in phase so that its largest entry is real and positive, and its real part
        is returned (the imaginary parts left are the gyroscopic coupling's, small where
        the carrier turns slowly).
        """
        phi = np.asarray(self.shapes)
        if not np.iscomplexobj(phi):
            return phi.astype(float)
        k = np.argmax(np.abs(phi), axis=0)
        turn = np.exp(-1j * np.angle(phi[k, np.arange(phi.shape[1])]))
        return (phi * turn).real

    def shape_columns(self) -> dict[str, object]:
        """Eigenvectors, one row per coordinate: its name, unit, modal mass weight, and the
        mass-normalised shape of every mode (``mode <k> <f> Hz``, k as in ``modes.csv``).

        Units of a row: translations (``.x``, ``.y``, ``.z``) m/kg^0.5, rotations
        (``.theta``) rad/(kg m^2)^0.5, so that ``phi^T M phi = 1`` for every mode. The
        column ``sqrt mass`` holds ``weights`` (kg^0.5 or (kg m^2)^0.5): ``sqrt mass *
        shape`` is the kinetic-energy amplitude. Gyroscopic modes: see
        :meth:`real_shapes`.
        """
        rot = [n.endswith(".theta") for n in self.dof_names]
        cols: dict[str, object] = {
            "dof": list(self.dof_names),
            "unit": ["rad/(kg m^2)^0.5" if r else "m/kg^0.5" for r in rot],
        }
        if self.weights is not None:
            cols["sqrt mass [kg^0.5 or (kg m^2)^0.5]"] = np.asarray(self.weights, float)
        phi = self.real_shapes()
        for k, f in enumerate(self.frequencies):
            cols[f"mode {k} {f:.6g} Hz [row unit]"] = phi[:, k]
        return cols
