"""The mutation campaign: hostile inputs to every pkmopt command and the Python module.

Run it with /usr/bin/python3 scripts/mutation_campaign.py (fuzz/campaign/main.py says how).
"""
