# Type stubs of the package mpcal (python/mpcal/__init__.py), for editors.
from os import PathLike
import enum
from typing import Any, Iterable, Literal, Mapping, Optional, Union

import numpy as np
import numpy.typing as npt

__version__: str

AccelUnits = Literal["mps2", "g", "counts"]
GyroUnits = Literal["rads", "dps", "counts"]
ArrayLike = npt.ArrayLike
Path = Union[str, PathLike[str]]

class Error(ValueError):
    kind: str
    advice: dict[str, Any]
    stage: Optional[str]
    stage_input: str
    figures: dict[str, Any]
    def __init__(self, message: str, kind: str = ..., advice: Optional[dict[str, Any]] = ...,
                 stage: Optional[str] = ..., stage_input: str = ...,
                 figures: Optional[dict[str, Any]] = ...) -> None: ...

class FindingKind(str, enum.Enum):
    LOG = "log"
    CLIPPED_POSITION = "clipped_position"
    NOT_STILL = "not_still"
    OUTLIER_EXCLUDED = "outlier_excluded"
    OUTLIER_KEPT = "outlier_kept"
    POORLY_DETERMINED = "poorly_determined"
    NO_REDUNDANCY = "no_redundancy"
    HALVES_DISAGREE = "halves_disagree"
    GYROSCOPE_NOT_CALIBRATED = "gyroscope_not_calibrated"
    GYROSCOPE_NOT_CONVERGED = "gyroscope_not_converged"
    GYROSCOPE_TOO_FEW_TURNS = "gyroscope_too_few_turns"
    GYROSCOPE_UNDETERMINED = "gyroscope_undetermined"
    GYROSCOPE_POORLY_DETERMINED = "gyroscope_poorly_determined"
    NOT_MEASURED = "not_measured"
    UPPER_BOUND = "upper_bound"
    TERM_DROPPED = "term_dropped"
    COMMENT_ONLY = "comment_only"
    FRAME_ROTATED = "frame_rotated"
    APPROXIMATED = "approximated"

class Finding:
    kind: Union[FindingKind, str]
    message: str
    advice: dict[str, Any]
    stage: Optional[str]
    figures: dict[str, Any]
    def __init__(self, kind: str, message: str, advice: Optional[dict[str, Any]] = ...,
                 stage: Optional[str] = ..., figures: Optional[dict[str, Any]] = ...) -> None: ...
    def __getattr__(self, name: str) -> Any: ...

class MpcalWarning(UserWarning):
    finding: Finding
    def __init__(self, finding: Union[Finding, str]) -> None: ...

class Recording:
    @property
    def t(self) -> npt.NDArray[np.float64]: ...
    @property
    def accel(self) -> npt.NDArray[np.float64]: ...
    @property
    def gyro(self) -> Optional[npt.NDArray[np.float64]]: ...
    @property
    def units(self) -> str: ...
    @property
    def gyro_units(self) -> str: ...
    @property
    def source(self) -> str: ...
    @property
    def warnings(self) -> list[str]: ...
    def __len__(self) -> int: ...

class Section:
    def __getattr__(self, name: str) -> Any: ...
    def __getitem__(self, name: str) -> Any: ...
    def __contains__(self, name: str) -> bool: ...
    def keys(self) -> Iterable[str]: ...
    def to_dict(self) -> dict[str, Any]: ...

class Calibration:
    @property
    def bias_mps2(self) -> npt.NDArray[np.float64]: ...
    @property
    def scale_factor_error(self) -> npt.NDArray[np.float64]: ...
    @property
    def non_orthogonality_rad(self) -> Section: ...
    @property
    def std(self) -> Optional[Section]: ...
    @property
    def gyroscope(self) -> Optional[Section]: ...
    @property
    def split_half(self) -> Optional[Section]: ...
    @property
    def input_units(self) -> str: ...
    gravity_mps2: float
    model: str
    format: str
    input: Section
    fit: Section
    positions: list[Section]
    warnings: list[str]
    findings: list[Finding]
    provenance: Section
    def __getattr__(self, name: str) -> Any: ...
    def to_dict(self) -> dict[str, Any]: ...
    def correct(self, accel: ArrayLike, gyro: Optional[ArrayLike] = ...,
                units: Optional[AccelUnits] = ..., gyro_units: Optional[GyroUnits] = ...
                ) -> tuple[npt.NDArray[np.float64], Optional[npt.NDArray[np.float64]]]: ...
    def save(self, path: Path) -> None: ...

def read_log(path: Path, *, columns: str = ..., units: AccelUnits = ...,
             gyro_units: GyroUnits = ..., time_unit: str = ..., rate_hz: float = ...,
             topic: str = ..., time: Literal["header", "receive"] = ...,
             gyro_log: str = ..., gyro_columns: str = ..., accel_topic: str = ...,
             gyro_topic: str = ...) -> Recording: ...

def calibrate(t: ArrayLike, accel: ArrayLike, gyro: Optional[ArrayLike] = ...,
              units: AccelUnits = ..., gravity: Optional[float] = ...,
              gyro_units: GyroUnits = ..., *, window_s: float = ..., min_static_s: float = ...,
              settle_s: float = ..., threshold: float = ..., max_still_g: float = ...,
              merge_gap_s: float = ..., merge_angle_deg: float = ..., range_g: float = ...,
              model: Literal["shin-el-sheimy-9", "bias-scale-6"] = ...,
              robust: Literal["none", "huber", "cauchy"] = ..., counts_per_g: float = ...,
              gyro_window_s: float = ..., gyro_g_sensitivity: Literal["auto", "on", "off"] = ...,
              calibrate_gyroscope: bool = ..., latitude_deg: Optional[float] = ...,
              height_m: float = ...) -> Calibration: ...

def load_calibration(path: Path) -> Calibration: ...

def detect(t: ArrayLike, accel: ArrayLike, units: AccelUnits = ...,
           gravity: Optional[float] = ..., *, window_s: float = ..., min_static_s: float = ...,
           settle_s: float = ..., threshold: float = ..., max_still_g: float = ...,
           merge_gap_s: float = ..., merge_angle_deg: float = ..., range_g: float = ...
           ) -> Section: ...

class Simulation:
    recording: Recording
    t: npt.NDArray[np.float64]
    accel: npt.NDArray[np.float64]
    gyro: Optional[npt.NDArray[np.float64]]
    units: str
    truth: Calibration
    still_ranges: npt.NDArray[np.int64]
    directions: npt.NDArray[np.float64]
    noise_std_mps2: npt.NDArray[np.float64]
    rate_hz: float

def simulate_static(*, preset: str = ..., seed: int = ..., positions: int = ...,
                    tilt_deg: float = ..., dwell_s: float = ..., turn_s: float = ...,
                    initial_rest_s: float = ..., rate_hz: float = ...,
                    units: AccelUnits = ..., counts_per_mps2: float = ...,
                    counts_offset: float = ..., gyro: bool = ..., gravity: float = ...
                    ) -> Simulation: ...

def noise(t: ArrayLike, accel: ArrayLike, gyro: Optional[ArrayLike] = ...,
          units: Literal["mps2", "g"] = ..., gyro_units: Literal["rads", "dps"] = ...,
          gravity: Optional[float] = ..., *, whole: bool = ..., confidence: float = ...,
          window_s: float = ..., min_static_s: float = ..., settle_s: float = ...,
          threshold: float = ..., max_still_g: float = ..., merge_gap_s: float = ...,
          merge_angle_deg: float = ..., range_g: float = ...) -> Section: ...

def simulate_noise(preset: Literal["consumer", "industrial"] = ..., duration_s: float = ...,
                   rate_hz: float = ..., seed: int = ...
                   ) -> tuple[Recording, dict[str, dict[str, list[float]]]]: ...

def export_formats() -> list[dict[str, Any]]: ...

def export(format: str, calibration: Optional[Union[Calibration, Path]] = ...,
           noise: Optional[Union[Mapping[str, Any], Path]] = ..., path: Optional[Path] = ...,
           *, rostopic: str = ..., rate_hz: Optional[float] = ...) -> str: ...

def import_calibration(format: str, *paths: Path, units: AccelUnits = ...,
                       gyro_units: GyroUnits = ..., gravity: Optional[float] = ...
                       ) -> Calibration: ...
