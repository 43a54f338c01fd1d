(define (problem lander-02)
  (:domain lander)
  (:init
    (flying)
    (= (h) 225.1) (= (v) -10)
    (= (mass) 1060.34) (= (fuel) 60.34) (= (burn-rate) 5)
    (= (gravity) 1.62) (= (thrust) 5153.3)
    (= (touch-height) 4) (= (safe-speed) 2.5))
  (:goal (and (landed))))
