"""What sk.intersect(..., certify=True) proves: the certificate and the arb-ball proofs of the stored points."""
