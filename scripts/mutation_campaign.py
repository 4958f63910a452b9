#!/usr/bin/env python3
"""The mutation campaign: hostile inputs to every pkmopt command and the Python module.

The campaign lives in fuzz/campaign/ (mutators, cases, option mutations, runner, checks, seed
inputs, main); fuzz/campaign/main.py documents the options. A short run is the CTest test
mutation_campaign_smoke.

  /usr/bin/python3 scripts/mutation_campaign.py --runs 100000 --jobs 2 --seed 1 --out DIR
"""
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from fuzz.campaign.main import main  # noqa: E402

if __name__ == "__main__":
    sys.exit(main())
