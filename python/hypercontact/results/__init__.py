"""The results of a run in one folder: curves.csv and summary.json
(:mod:`.writer`), fields.xdmf (:mod:`.fields`), curves.png and deformed.png
(:mod:`.drawing`)."""
from .fields import FRICTION_FIELDS, NonFiniteField, first_piola_stress, von_mises
from .writer import SCALED, ResultsWriter

__all__ = ["ResultsWriter", "NonFiniteField", "FRICTION_FIELDS", "SCALED", "first_piola_stress", "von_mises"]
