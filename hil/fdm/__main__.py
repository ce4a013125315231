"""python -m hil.fdm <aircraft_dir> <out_root>: writes the generated JSBSim model to look at."""
import sys

from .model_xml import main

sys.exit(main(sys.argv))
