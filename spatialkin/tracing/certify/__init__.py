"""What sk.intersect(..., certify=True) proves: the certificate, the proven boxes round the stored points, the tubes
along the curves, the trims' crossings."""
