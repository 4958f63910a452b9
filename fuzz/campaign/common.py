"""Constants shared by the campaign: the repository, the commands, the run files. (the mutation campaign: fuzz/campaign/main.py)."""

import argparse
import concurrent.futures
import csv
import errno
import hashlib
import io
import json
import math
import multiprocessing
import os
import random
import re
import resource
import shlex
import shutil
import signal
import stat
import struct
import subprocess
import sys
import threading
import time
import traceback
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent.parent
CAMPAIGN_VERSION = "1"

COMMANDS = [
    "describe", "analyze", "fk", "workspace", "trajectory", "calibration-poses",
    "simulate-measurements", "calibrate", "validate", "run", "export", "compare", "draw",
    "task-poses", "python",
]

# What a failed `run` may leave in its --out folder: the journal it resumes from (its results,
# study.resolved.yaml included, go into place together or not at all).
RUN_JOURNAL_FILES = {"journal.txt", "evaluations.csv", "run.lock", "journal.damaged.txt"}
PYTHON = "/usr/bin/python3"
