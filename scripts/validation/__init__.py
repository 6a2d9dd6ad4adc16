"""Validation harness of scripts/validate.py: measures, scenario generators, experiments, plots."""
