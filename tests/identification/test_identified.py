"""The identification's result, typed (orthocontact.identification.identified);
its JSON object read back: tests/identification/test_identified_json.py."""
from orthocontact.identification import identified


def test_a_summary_lists_the_five_and_what_else_was_fitted():
    assert identified.reported_names({"l1_l2_ratio": 1, "mu1": 2}) == [*identified.REPORTED, "l1_l2_ratio"]
    assert identified.reported_names({"c_strip": 1, "f_int": 2}) == [*identified.REPORTED, "c_strip", "f_int"]
